// Parameter-server tree (XmlRpc) -> YAML, so the node reuses the core's scene parser and its messages.
#pragma once

#include <set>
#include <string>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

namespace top_sim_ros {

// Converts a value; throws std::runtime_error naming `where` for types YAML cannot hold (dates, binary).
YAML::Node to_yaml(XmlRpc::XmlRpcValue& value, const std::string& where);

// The struct `tree` as a YAML map without the keys in `drop` (the node's own parameters).
YAML::Node scene_yaml(XmlRpc::XmlRpcValue& tree, const std::set<std::string>& drop, const std::string& where);

}  // namespace top_sim_ros
