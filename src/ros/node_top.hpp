// One top of the node: its simulator and pacing, its own topics (built here, as turtlesim's Turtle builds its
// own), its command input and its output state (docs/ros.md, "Many tops"). Each top integrates on its own (own stepper, events, contact modes, Pacer), so a costly top falls
// behind alone instead of slowing the others.
#pragma once

#include <chrono>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>

#include <ros/ros.h>

#include "conversions.hpp"
#include "marker_stream.hpp"
#include "top_input.hpp"
#include "trail.hpp"
#include "top_sim/pacing.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace top_sim_ros {

// What the publishing side keeps per top.
struct TopOutput {
  ros::Publisher state, path;
  // Subscriber counts kept by the publishers' connect callbacks: Publisher::getNumSubscribers() looks the topic up
  // among all of the node's publications by name, which with thousands of tops cost more than the physics.
  // Shared with the callbacks, which roscpp may still run after the top is gone.
  std::shared_ptr<int> state_subscribers = std::make_shared<int>(0), path_subscribers = std::make_shared<int>(0);
  // Their values as of the last subscription change anywhere (StateOutput refreshes them then): read every tick
  // next to the trail, where the counts' own allocations are a cache miss per top per tick.
  int state_readers = 0, path_readers = 0;
  Trail trail;              // contact-point trail
  MarkerStream markers;     // what ~markers has sent of the top
  ros::Time last_tf_stamp;  // tf only when time moved (a repeated stamp is TF_REPEATED_DATA to listeners)
  ros::Time latched_stamp;  // the stopped time whose frames are on /tf_static (StateOutput::latch_frames)
  Eigen::Vector3d grid_at = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());  // as last sent
  ros::Time grid_stamp;
};

// A top's own topics: top_state and path, and the command topics (TopInput). Built on any thread by
// NodeTop::open_topics, installed on the loop's thread by NodeTop::install.
struct TopTopics {
  ros::Publisher state, path;
  std::unique_ptr<TopInput> input;
};

class NodeTop {
 public:
  // `node_time`: the node's simulated time at creation (0 for the launch-time top); stamps are
  // stamp origin + node_time + the top's own simulated time, so a spawned top starts at the node's current stamp.
  // The launch-time top keeps the node's names (~top_state, frames plane and top); a spawned one lives under NAME/.
  NodeTop(std::string name, bool launch_top, top_sim::Scene scene, const Frames& frames, double node_time,
          double real_time_factor, double rate, double wall);

  // One tick: the Pacer's target for `wall`, reached within about `budget` wall seconds from `start` (a steady
  // clock reading just taken), or short of it.
  void advance(double wall, double budget, bool paused,
               std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());
  void reset(double wall);                          // to the scene's initial state; time keeps running forward
  void reanchor(double wall, bool clear_window);    // after pause, resume, a new factor
  // This top alone paused (~pause pauses the node, every top): its time stays, commands still apply.
  void set_paused(bool paused, double wall);
  bool paused() const { return paused_; }
  // A TopCommand for this top (its own ~command or ~tops/command): checked as a whole first, the core's fields
  // against the model they will meet (the scene's when it resets), then reset, pause or resume, the fields. "" or
  // why nothing was applied; `applied` gets the core's fields that were submitted.
  std::string command(const top_sim::TopCommand& m, double wall, top_sim::Command& applied);
  // Logs a new fault or a change of the behind state once (spawned tops' lines are throttled node-wide).
  void report(double real_time_factor, double publish_rate, bool paused);

  // The one place a top's topics are built, under `pnh` + prefix(): top_state and path (each subscription change
  // counted in output's counters and in `changes`), and inclination, spin and command, whose commands go to
  // `submit`. Thread-safe (the node handle and the top's constant parts): the TopicOpener calls it off the loop.
  TopTopics open_topics(ros::NodeHandle& pnh, const std::shared_ptr<unsigned>& changes, SubmitCommand submit,
                        ApplyMessage apply, RejectionLog& log) const;
  void install(TopTopics topics);  // on the loop's thread

  const std::string& name() const { return name_; }
  top_sim::Simulator& sim() { return *sim_; }
  const top_sim::Simulator& sim() const { return *sim_; }
  top_sim::Pacer& pacer() { return pacer_; }
  const top_sim::Pacer& pacer() const { return pacer_; }
  const Frames& frames() const { return frames_; }
  double stamp_offset() const { return node_time_; }
  bool launch_top() const { return prefix_.empty(); }
  const std::string& prefix() const { return prefix_; }  // "" or "NAME/": topic names relative to ~

  std::size_t take_steps();  // integrator steps since the last call
  std::size_t mode_switches() const { return mode_switches_; }

  TopOutput output;

 private:
  std::string name_, prefix_;
  // What a tick reads, together (a thousand tops' first touches are what a tick costs beyond the arithmetic).
  std::unique_ptr<top_sim::Simulator> sim_;
  top_sim::Pacer pacer_;
  Frames frames_;
  double node_time_;
  std::size_t steps_reported_ = 0, mode_switches_ = 0;
  bool fault_reported_ = false, behind_reported_ = false;
  bool paused_ = false;  // this top alone (TopCommand's set_paused)
  std::unique_ptr<TopInput> input_;  // its subscribers, once installed
};

// The frames of a spawned top NAME: NAME/<plane>, NAME/<top>, NAME/<contact> under the node's world frame.
Frames spawned_frames(const Frames& node_frames, const std::string& name);

}  // namespace top_sim_ros
