// dynamic_reconfigure (cfg/TopSim.cfg) for the launch-time top's physics and the node's pacing (docs/ros.md).
// The .cfg declares no ranges: a bad value is refused with a warning and the values in force are shown again
// (no silent clamps). Physics changes go through the same validated command path as the topics.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include "top_sim/TopSimConfig.h"
#include "top_sim/command.hpp"
#include "top_sim/scene.hpp"

namespace top_sim_ros {

struct ReconfigureHooks {
  std::function<std::string(const top_sim::Command&)> submit;  // to the launch-time top: "" or why refused
  std::function<void(double)> set_real_time_factor;             // called with valid values only
  std::function<void(double)> set_publish_rate;
};

class NodeReconfigure {
 public:
  // Shows the values in force at start: the launch-time top's scene's (dynamic_reconfigure's values found under ~
  // are folded into it).
  NodeReconfigure(ros::NodeHandle& nh, ros::NodeHandle& pnh, const top_sim::Scene& scene, double real_time_factor,
                  double publish_rate, ReconfigureHooks hooks);

  // Records the values an accepted command (from any source) or a reset's scene put in force, and marks them for the
  // slow timer to push to dynamic_reconfigure (never on a command's path).
  void record_for_push(const top_sim::Command& applied);
  void record_scene_for_push(const top_sim::Scene& scene);

 private:
  void on_reconfigure(top_sim::TopSimConfig& cfg, uint32_t level);
  bool reconfigured_friction(const top_sim::TopSimConfig& cfg, top_sim::FrictionChange& change);
  void reconfigure_pacing(top_sim::TopSimConfig& cfg, uint32_t level);

  ReconfigureHooks hooks_;
  boost::recursive_mutex mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<top_sim::TopSimConfig>> server_;
  top_sim::TopSimConfig config_;
  bool ready_ = false, dirty_ = false;
  ros::WallTimer timer_;
};

}  // namespace top_sim_ros
