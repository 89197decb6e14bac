// The node's /diagnostics status (docs/ros.md, "Diagnostics"): the node's pacing and cost, counts over all tops,
// and the launch-time top in detail.
#pragma once

#include <cstddef>
#include <string>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>

#include "top_set.hpp"

namespace top_sim_ros {

// What the node knows beyond its tops.
struct NodeStatus {
  bool paused = false;
  double requested_factor = 1.0;
  double publish_rate = 200.0;
  std::size_t published = 0;  // periods published since start
  std::size_t rejected = 0;   // commands rejected since start
  std::string lcm;            // "off", "on: ...", "error: ..."
  std::size_t topics_pending = 0;  // tops whose own topics are still being advertised (topic_opener.hpp)
};

class NodeDiagnostics {
 public:
  explicit NodeDiagnostics(double wall);
  // After each tick's physics: the steps it took and the CPU it cost.
  void add_physics(std::size_t steps, double cpu_seconds);
  void fill(diagnostic_updater::DiagnosticStatusWrapper& st, TopSet& tops, const NodeStatus& node, double wall);

 private:
  double wall_, cpu_, step_cpu_ = 0.0;
  std::size_t steps_ = 0, published_ = 0;
};

double process_cpu_seconds();

}  // namespace top_sim_ros
