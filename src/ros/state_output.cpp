#include "state_output.hpp"

#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <visualization_msgs/MarkerArray.h>

#include "top_sim/TopState.h"
#include "top_sim/TopStateArray.h"

namespace top_sim_ros {

StateOutput::StateOutput(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParameters& params, double stamp_origin)
    : params_(params), stamp_origin_(stamp_origin) {
  markers_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 2);
  states_ = pnh.advertise<top_sim::TopStateArray>("top_states", 10);
  if (params_.publish_clock) clock_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  if (!params_.lcm_url.empty()) open_lcm();
}

namespace {

template <class M>
ros::Publisher counted(ros::NodeHandle& pnh, const std::string& topic, uint32_t queue,
                       const std::shared_ptr<int>& count) {
  return pnh.advertise<M>(
      topic, queue, [count](const ros::SingleSubscriberPublisher&) { ++*count; },
      [count](const ros::SingleSubscriberPublisher&) { --*count; });
}

}  // namespace

// The callbacks run in spinOnce() on the loop's thread.
void StateOutput::open(NodeTop& top, ros::NodeHandle& pnh) {
  TopOutput& out = top.output;
  out.state = counted<top_sim::TopState>(pnh, top.prefix() + "top_state", 10, out.state_subscribers);
  out.path = counted<nav_msgs::Path>(pnh, top.prefix() + "path", 2, out.path_subscribers);
}

ros::Time StateOutput::stamp(const NodeTop& top) const {
  return ros::Time(stamp_origin_ + top.stamp_offset() + top.sim().time());
}

namespace {

// Marker namespaces carry the top's prefix, so rviz keeps one set per top ("" for the launch-time top).
void add_markers(const NodeTop& top, const top_sim::Snapshot& s, const ros::Time& stamp,
                 visualization_msgs::MarkerArray& out) {
  visualization_msgs::MarkerArray one;
  to_markers(s, top.sim().model().top, stamp, top.frames(), one);
  for (auto& m : one.markers) {
    m.ns = top.prefix() + m.ns;
    out.markers.push_back(m);
  }
}

}  // namespace

void StateOutput::close(NodeTop& top) {
  visualization_msgs::MarkerArray gone;
  add_markers(top, top.sim().snapshot(), stamp(top), gone);
  for (auto& m : gone.markers) m.action = visualization_msgs::Marker::DELETE;
  markers_.publish(gone);
}

void StateOutput::publish(TopSet& tops, double wall, bool paused, double requested_factor) {
  const bool array = states_.getNumSubscribers() > 0;
  top_sim::TopStateArray all;
  std::vector<geometry_msgs::TransformStamped> tf;
  tf.reserve(2 * tops.size());
  if (array) {
    all.names.reserve(tops.size());
    all.states.reserve(tops.size());
  }
  for (auto& t : tops) {
    NodeTop& top = *t;
    const top_sim::Snapshot s = top.sim().snapshot();
    if (!top_sim::all_finite(s)) {
      ROS_ERROR_THROTTLE(1.0, "top_sim_node: top %s: non-finite state at t = %g s: not published (call ~reset)",
                         top.name().c_str(), s.t);
      continue;
    }
    const ros::Time stamp = this->stamp(top);
    update_trail(top, s, stamp);
    add_transforms(top, s, stamp, tf);
    if (top.launch_top()) publish_lcm(s, top.pacer().achieved_factor());
    const bool subscribed = *top.output.state_subscribers > 0;
    if (!subscribed && !array) continue;  // a message nobody reads is not built (thousands of tops)
    top_sim::TopState msg;
    to_msg(s, stamp, top.frames().plane, msg);
    msg.real_time_factor = top.pacer().achieved_factor();
    msg.requested_real_time_factor = requested_factor;
    msg.paused = paused;
    if (subscribed) top.output.state.publish(msg);
    if (array) {
      all.names.push_back(top.name());
      all.states.push_back(std::move(msg));
    }
  }
  if (array) {
    all.header.stamp = stamp(tops.launch_top());
    all.header.frame_id = params_.frames.world;
    states_.publish(all);
  }
  if (!tf.empty()) tf_.sendTransform(tf);
  publish_clock(tops.launch_top());
  publish_markers(tops, wall);
  publish_paths(tops, wall);
  ++published_;
}

// tf only when the top's time moved (a repeated stamp is dropped by listeners as TF_REPEATED_DATA).
void StateOutput::add_transforms(NodeTop& top, const top_sim::Snapshot& s, const ros::Time& stamp,
                                 std::vector<geometry_msgs::TransformStamped>& tf) {
  if (!params_.publish_tf || !(stamp > top.output.last_tf_stamp)) return;
  geometry_msgs::TransformStamped wp, pt;
  to_transforms(s, stamp, top.frames(), wp, pt);
  tf.push_back(wp);
  tf.push_back(pt);
  top.output.last_tf_stamp = stamp;
}

// /clock follows the launch-time top, which is never removed and whose time never goes back (reset included).
void StateOutput::publish_clock(const NodeTop& launch_top) {
  const ros::Time clock = stamp(launch_top);
  if (!params_.publish_clock || !(clock > last_clock_)) return;
  rosgraph_msgs::Clock c;
  c.clock = clock;
  clock_.publish(c);
  last_clock_ = clock;
}

void StateOutput::publish_markers(TopSet& tops, double wall) {
  if (wall - last_marker_wall_ < 1.0 / params_.marker_rate || markers_.getNumSubscribers() == 0) return;
  visualization_msgs::MarkerArray markers;
  for (auto& t : tops) {
    const top_sim::Snapshot s = t->sim().snapshot();
    if (top_sim::all_finite(s)) add_markers(*t, s, stamp(*t), markers);
  }
  markers_.publish(markers);
  last_marker_wall_ = wall;
}

void StateOutput::publish_paths(TopSet& tops, double wall) {
  if (wall - last_path_wall_ < 1.0 / params_.path_rate) return;
  for (auto& t : tops) {
    TopOutput& out = t->output;
    if (*out.path_subscribers <= 0) continue;
    trim_trail(out.trail);
    out.trail.header.stamp = stamp(*t);
    out.trail.header.frame_id = t->frames().plane;
    out.path.publish(out.trail);
  }
  last_path_wall_ = wall;
}

// Contact-point trail: a pose each time the point has moved path_resolution; path_length published at most.
void StateOutput::update_trail(NodeTop& top, const top_sim::Snapshot& s, const ros::Time& stamp) {
  nav_msgs::Path& path = top.output.trail;
  const Eigen::Vector3d p = s.contact_point;
  if (!path.poses.empty() && params_.path_resolution > 0.0) {
    const auto& q = path.poses.back().pose.position;
    if ((p - Eigen::Vector3d(q.x, q.y, q.z)).norm() < params_.path_resolution) return;
  }
  geometry_msgs::PoseStamped ps;
  ps.header.stamp = stamp;
  ps.header.frame_id = top.frames().plane;
  ps.pose.position.x = p.x();
  ps.pose.position.y = p.y();
  ps.pose.position.z = p.z();
  ps.pose.orientation.w = 1.0;
  path.poses.push_back(ps);
  // Trimmed in chunks (erasing the oldest pose each tick moved path_length poses per tick and top).
  const std::size_t keep = static_cast<std::size_t>(params_.path_length);
  if (path.poses.size() > keep + keep / 4 + 1) trim_trail(path);
}

void StateOutput::trim_trail(nav_msgs::Path& path) const {
  const std::size_t keep = static_cast<std::size_t>(params_.path_length);
  if (path.poses.size() > keep) path.poses.erase(path.poses.begin(), path.poses.begin() + (path.poses.size() - keep));
}

void StateOutput::publish_lcm(const top_sim::Snapshot& s, double achieved_factor) {
#ifdef TOP_SIM_HAVE_LCM
  if (lcm_ && !lcm_->publish(s, achieved_factor) && !lcm_send_failed_) {
    ROS_ERROR("top_sim_node: LCM publish on %s failed (reported once)", lcm_->channel().c_str());
    lcm_send_failed_ = true;
  }
#else
  (void)s;
  (void)achieved_factor;
#endif
}

// LCM is optional: a failure is logged and the node publishes on ROS only.
void StateOutput::open_lcm() {
  const std::string& url = params_.lcm_url;
#ifdef TOP_SIM_HAVE_LCM
  lcm_ = std::make_unique<top_sim_lcm::Publisher>(url, params_.lcm_channel);
  if (!lcm_->ok()) {
    lcm_status_ = "error: " + lcm_->error();
    ROS_ERROR("top_sim_node: lcm_url = '%s': %s; LCM is off, ROS publishing continues", url.c_str(),
              lcm_->error().c_str());
    lcm_.reset();
  } else {
    lcm_status_ = "on: " + url + ", channel " + params_.lcm_channel;
    ROS_INFO("top_sim_node: LCM on '%s', channel %s", url.c_str(), params_.lcm_channel.c_str());
  }
#else
  lcm_status_ = "error: this build has no LCM support";
  ROS_ERROR("top_sim_node: lcm_url = '%s': this build has no LCM support; ROS publishing continues", url.c_str());
#endif
}

}  // namespace top_sim_ros
