// A scene: everything one run needs, loaded and validated from YAML (docs/interfaces.md).
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "top_sim/command.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/model.hpp"
#include "top_sim/scene_error.hpp"
#include "top_sim/state.hpp"

namespace YAML { class Node; }

namespace top_sim {

enum class StartKind { tilted, stationary };

struct InitialConditions {
  StartKind start = StartKind::tilted;
  double tilt = 0.1;                  // from the world vertical [rad]
  double tilt_azimuth = 0.0;          // about the world vertical, from world x [rad]
  double spin = 200.0;                // omega . f_hat of the shell [rad/s]
  Eigen::Vector2d angular_velocity_transverse = Eigen::Vector2d::Zero();  // world (x, y, 0) [rad/s]
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  double gap = 0.0;                   // height of the tip-sphere centre above R [m] (> 0: starts in flight)
  double gap_rate = 0.0;              // its rate [m/s] (> 0: starts in flight)
  double rotor_spin = 0.0;            // absolute rotor spin Omega [rad/s] (top.rotor.spin)
};

struct ScriptedEvent {
  double t = 0.0;
  Command command;
};

// How a viewer shows the scene's story (scene key `view`); the node and rviz follow it unless the launch overrides.
// 0 and `unset` leave the viewer's own default.
enum class ViewCamera { unset, low, top, follow };
const char* to_string(ViewCamera camera);
struct ViewHint {
  ViewCamera camera = ViewCamera::unset;  // low: from the side, near the plane; top: from above; follow: the top's frame
  double distance = 0.0;                  // the camera's distance from its focus [m]
  double real_time_factor = 0.0;          // simulated seconds per wall second in the node
};

struct Scene {
  std::string source = "<scene>";  // file name, for messages
  ViewHint view;
  Model model;
  InitialConditions initial;
  IntegratorSettings integrator;
  std::vector<ScriptedEvent> events;
  double duration = 10.0;           // default run length [s]
  std::vector<std::string> warnings;  // e.g. the friction clamp, said once
};

// Loads a scene file; `top` and `friction` may name files in <config>/tops and <config>/planes.
Scene load_scene(const std::string& path);

// Parses a scene from an already-loaded YAML tree (e.g. from the ROS parameter server).
// `config_dir` is where tops/ and planes/ are looked up ("" = the installed config).
Scene parse_scene(const YAML::Node& root, const std::string& source, const std::string& config_dir = "");

// Parses a scene given as YAML text (a ROS parameter, a spawn request): the same checks as load_scene, so a key
// given twice or a bad number is refused as it is in a file. Empty text = every key at its default.
Scene parse_scene_text(const std::string& text, const std::string& source, const std::string& config_dir = "");

// The initial state the scene asks for (tilted start or exact sleeping state).
StateVector initial_state(const Scene& scene);

}  // namespace top_sim
