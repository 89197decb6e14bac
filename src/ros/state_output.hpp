// Publishing (docs/ros.md, "Topics"): per top its TopState, tf and contact-point path; for all tops the
// top_states array and the markers; /clock and LCM from the launch-time top. Nothing non-finite is published.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Path.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <ros/ros.h>

#include "node_parameters.hpp"
#include "top_set.hpp"
#include "top_sim/TopStateArray.h"
#include "top_sim/pose.hpp"
#include "top_sim/snapshot.hpp"
#ifdef TOP_SIM_HAVE_LCM
#include "lcm_publisher.hpp"
#endif

namespace top_sim_ros {

class StateOutput {
 public:
  // Advertises the node-wide topics under `pnh` (markers, top_states; /clock when asked) and opens LCM.
  StateOutput(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParameters& params, double stamp_origin);

  // A new top: its marker state, and its counters refreshed before its first publication (loop's thread).
  void open(NodeTop& top);
  // Advertises the top's top_state and path (any thread: reads only the top's name and its counters' pointers).
  // Shared with a top's publishers' callbacks (NodeTop::open_topics): counts every subscription change.
  const std::shared_ptr<unsigned>& subscription_changes() const { return subscription_changes_; }
  void close(NodeTop& top);                       // deletes its markers in rviz
  void clear_trail(NodeTop& top) { top.output.trail.clear(); }
  const std::string& followed() const { return follow_; }

  // One period's output for every top: one TFMessage with every top's frames, one top_states array; the messages
  // are kept from tick to tick and refilled in place (no per-top allocation with thousands of tops).
  void publish(TopSet& tops, double wall, bool paused, double requested_factor);

  ros::Time stamp(const NodeTop& top) const;  // origin + the top's spawn offset + its simulated time
  const std::string& lcm_status() const { return lcm_status_; }
  std::size_t published() const { return published_; }

 private:
  struct TickFlags {  // who reads what this tick
    bool array = false;
    bool paused = false;
    double requested_factor = 0.0;
  };
  void refresh_readers(TopSet& tops);  // the tops' subscriber mirrors, after a subscription changed
  void publish_top(NodeTop& top, const TickFlags& flags);
  void fill_state(NodeTop& top, const top_sim::Snapshot& s, const ros::Time& stamp, const TickFlags& flags,
                  top_sim::TopState& msg) const;
  top_sim::TopState& next_state(const NodeTop& top);
  geometry_msgs::TransformStamped& next_transform();
  void add_transforms(NodeTop& top, const top_sim::TopPose& pose, const ros::Time& stamp);
  void latch_frames(NodeTop& top, const top_sim::TopPose& pose, const ros::Time& stamp);
  void set_static(const geometry_msgs::TransformStamped& t);
  void publish_static();
  void publish_clock(const NodeTop& launch_top);
  void on_follow(const std::string& name) { follow_request_ = name; }
  NodeTop& followed_top(TopSet& tops);
  void add_follow_transform(TopSet& tops);
  void add_grid_transform(NodeTop& top, const top_sim::TopPose& pose, const ros::Time& stamp);
  MarkerStyle style(const NodeTop& top) const;
  void publish_markers(TopSet& tops, double wall);
  void publish_paths(TopSet& tops, double wall);
  void publish_lcm(const top_sim::Snapshot& s, double achieved_factor, double requested_factor, bool paused,
                   const char* friction_law);
  void open_lcm();

  NodeParameters params_;
  double stamp_origin_;
  ros::Publisher markers_, states_, clock_, tf_, tf_static_;
  ros::Subscriber follow_sub_;
  std::string follow_parent_;            // the contact frame the follow frame is attached to on /tf_static
  // /tf_static's latched message holds every transform sent there (the follow frame, the frames of stopped tops):
  // a later one replaces it for listeners that start late. By child frame; published when changed.
  std::map<std::string, geometry_msgs::TransformStamped> static_;
  bool static_changed_ = false;
  std::string follow_, follow_request_;  // the followed top's name ("" = launch-time top); a name asked on ~follow
  bool markers_watched_ = false;         // ~markers has subscribers this tick: contact frames are needed
  // ~markers' subscriptions so far (counted by its connect callback) and as last seen by a marker tick.
  std::shared_ptr<unsigned> marker_subscriptions_ = std::make_shared<unsigned>(0);
  unsigned marker_subscriptions_seen_ = 0;
  // Subscription changes of the tops' own topics (shared with the publishers' callbacks) and as last refreshed.
  std::shared_ptr<unsigned> subscription_changes_ = std::make_shared<unsigned>(0);
  unsigned changes_seen_ = 0;
  // The tick's messages, kept across ticks: the first `states_used_` / `tf_used_` entries are this tick's.
  top_sim::TopStateArray all_;
  std::vector<const NodeTop*> named_;  // the top whose name all_.names[i] holds (nullptr: none)
  top_sim::TopState own_;  // a top's own top_state when the array is not read
  std::vector<std::pair<NodeTop*, std::size_t>> own_in_array_;  // subscribed tops and their entries in all_
  tf2_msgs::TFMessage tf_msg_;
  nav_msgs::Path path_;
  std::size_t states_used_ = 0, tf_used_ = 0;
  ros::Time last_clock_, last_follow_stamp_;
  double last_marker_wall_ = 0.0, last_path_wall_ = 0.0;
  std::size_t published_ = 0;
  std::string lcm_status_ = "off";
#ifdef TOP_SIM_HAVE_LCM
  std::unique_ptr<top_sim_lcm::Publisher> lcm_;
  bool lcm_send_failed_ = false;
#endif
};

}  // namespace top_sim_ros
