// Parameter-server tree (XmlRpc) -> YAML, so the node reuses the core's scene parser and its messages.
#pragma once

#include <set>
#include <string>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include "top_sim/command.hpp"
#include "top_sim/model.hpp"
#include "top_sim/scene.hpp"

namespace top_sim_ros {

// Converts a value; throws std::runtime_error naming `where` for types YAML cannot hold (dates, binary).
YAML::Node to_yaml(XmlRpc::XmlRpcValue& value, const std::string& where);

// The keys of cfg/TopSim.cfg that change the physics (alpha, spin, friction_law, the friction parameters, the
// finite contact and air).
const std::set<std::string>& reconfigure_physics_keys();

// Values of those keys found in `tree` at start (set by the user, or left by dynamic_reconfigure) as one command
// over `model`'s friction law; throws std::runtime_error naming the parameter when one is not a number or a law.
// The caller validates the command through the core like any other.
top_sim::Command start_command(XmlRpc::XmlRpcValue& tree, const top_sim::Model& model, const std::string& where);

// The launch-time top's scene: `scene` with a validated start command folded in (its model fields applied by the core
// as a command would apply them, its spin as initial.spin), so the top starts there and ~reset returns there without
// a command. Throws std::runtime_error when a stationary start has no sleeping state at the folded values.
top_sim::Scene start_scene(top_sim::Scene scene, const top_sim::Command& start);

}  // namespace top_sim_ros
