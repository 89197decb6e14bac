#include "state_output.hpp"

#include <algorithm>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <boost/function.hpp>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>
#include <visualization_msgs/MarkerArray.h>

#include "markers.hpp"

#include "top_sim/TopState.h"

namespace top_sim_ros {

namespace {

// The law in force (the scene's, as commands changed it): TopState's and LCM's friction_law; the snapshot has no law.
const char* friction_law(const NodeTop& top) { return top_sim::to_string(top.sim().model().friction.kind); }

}  // namespace

StateOutput::StateOutput(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParameters& params, double stamp_origin)
    : params_(params), stamp_origin_(stamp_origin), follow_request_(params.follow) {
  // A new subscriber (rviz, rosbag record) gets every marker at the next tick, the trail's chunks included.
  markers_ = pnh.advertise<visualization_msgs::MarkerArray>(
      "markers", 2, [count = marker_subscriptions_](const ros::SingleSubscriberPublisher&) { ++*count; });
  const boost::function<void(const std_msgs::String::ConstPtr&)> follow = [this](const std_msgs::String::ConstPtr& m) {
    on_follow(m->data);
  };
  follow_sub_ = pnh.subscribe<std_msgs::String>("follow", 1, follow);
  states_ = pnh.advertise<top_sim::TopStateArray>("top_states", 10);
  tf_ = nh.advertise<tf2_msgs::TFMessage>("/tf", 100);  // as tf2_ros::TransformBroadcaster does, message kept
  tf_static_ = nh.advertise<tf2_msgs::TFMessage>("/tf_static", 1, true);  // latched, as tf2's static broadcaster
  if (params_.publish_clock) clock_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  if (!params_.lcm_url.empty()) open_lcm();
}


void StateOutput::open(NodeTop& top) {
  top.output.markers.follow_speed(0.0, params_.grid_pitch);  // the grid frame's pitch before the first marker tick
  ++*subscription_changes_;  // the new top's mirrors are refreshed before its first publication
}

void StateOutput::refresh_readers(TopSet& tops) {
  if (*subscription_changes_ == changes_seen_) return;
  for (auto& t : tops) {
    t->output.state_readers = *t->output.state_subscribers;
    t->output.path_readers = *t->output.path_subscribers;
  }
  changes_seen_ = *subscription_changes_;
}

ros::Time StateOutput::stamp(const NodeTop& top) const {
  return ros::Time(stamp_origin_ + top.stamp_offset() + top.sim().time());
}

MarkerStyle StateOutput::style(const NodeTop& top) const {
  MarkerStyle style;
  style.name = top.name();
  style.color_by = params_.color_by;
  style.grid_pitch = top.output.markers.grid_pitch();
  style.grid_line_pitch = params_.grid_pitch;
  style.grid_cells = params_.grid_cells;
  return style;
}

// Marker namespaces carry the top's prefix, so rviz keeps one set per top ("" for the launch-time top).
void StateOutput::close(NodeTop& top) {
  std::fill(named_.begin(), named_.end(), nullptr);  // a top spawned later may get the killed one's address
  const Frames& f = top.frames();
  for (const std::string* child : {&f.plane, &f.top, &f.contact, &f.grid})  // no stale latched frames of it
    static_changed_ |= static_.erase(*child) > 0;
  publish_static();
  visualization_msgs::MarkerArray gone;
  top.output.markers.remove_all(top.sim().snapshot(), top.sim().model().top, top.frames(), style(top), top.prefix(),
                                stamp(top), gone);
  markers_.publish(gone);
}

void StateOutput::publish(TopSet& tops, double wall, bool paused, double requested_factor) {
  TickFlags flags;
  flags.array = states_.getNumSubscribers() > 0;
  flags.paused = paused;
  flags.requested_factor = requested_factor;
  markers_watched_ = markers_.getNumSubscribers() > 0;
  refresh_readers(tops);
  states_used_ = tf_used_ = 0;
  own_in_array_.clear();
  for (auto& t : tops) publish_top(*t, flags);
  if (flags.array) {
    all_.names.resize(states_used_);
    all_.states.resize(states_used_);
    all_.header.stamp = stamp(tops.launch_top());
    all_.header.frame_id = params_.frames.world;
    states_.publish(all_);
  }
  for (const auto& [top, i] : own_in_array_) top->output.state.publish(all_.states[i]);
  add_follow_transform(tops);
  publish_static();
  if (tf_used_ > 0) {
    tf_msg_.transforms.resize(tf_used_);
    tf_.publish(tf_msg_);
  }
  publish_clock(tops.launch_top());
  publish_markers(tops, wall);
  publish_paths(tops, wall);
  ++published_;
}

// A top's trail and frames come from its pose; the full snapshot (the sample's analysis) only when a TopState of it
// is read, or for the launch-time top (LCM, diagnostics): thousands of tops seen through tf alone cost no sample.
void StateOutput::publish_top(NodeTop& top, const TickFlags& flags) {
  // A subscriber may connect before a background-advertised publisher is installed (topic_opener.hpp).
  const bool subscribed = top.output.state_readers > 0 && top.output.state;
  const bool full = flags.array || subscribed || top.launch_top();
  top_sim::Snapshot s;
  if (full) s = top.sim().snapshot();
  const top_sim::TopPose pose = full ? top_sim::top_pose(s) : top.sim().pose();  // the snapshot holds it
  if (full ? !top_sim::all_finite(s) : !top_sim::all_finite(pose)) {
    ROS_ERROR_THROTTLE(1.0, "top_sim_node: top %s: non-finite state at t = %g s: not published (call ~reset)",
                       top.name().c_str(), pose.t);
    return;
  }
  const ros::Time stamp = this->stamp(top);
  top.output.trail.add(pose.contact_point, stamp, params_.path_resolution,
                       static_cast<std::size_t>(params_.path_length));
  add_transforms(top, pose, stamp);
  if (top.launch_top())
    publish_lcm(s, top.pacer().achieved_factor(), flags.requested_factor, flags.paused || top.paused(),
                friction_law(top));
  if (!subscribed && !flags.array) return;  // a message nobody reads is not built (thousands of tops)
  top_sim::TopState& msg = flags.array ? next_state(top) : own_;
  fill_state(top, s, stamp, flags, msg);
  if (!subscribed) return;
  // With the array read, from its entry after the loop: roscpp's I/O thread walks all of the node's publications
  // (two per top) each time a publish wakes it, so the tick's messages go out back to back.
  if (flags.array)
    own_in_array_.emplace_back(&top, states_used_ - 1);
  else
    top.output.state.publish(msg);  // serialised now: own_ serves the next top
}

void StateOutput::fill_state(NodeTop& top, const top_sim::Snapshot& s, const ros::Time& stamp,
                             const TickFlags& flags, top_sim::TopState& msg) const {
  to_msg(s, stamp, top.frames().plane, msg);
  msg.real_time_factor = top.pacer().achieved_factor();
  msg.requested_real_time_factor = flags.requested_factor;
  msg.paused = flags.paused || top.paused();  // the node, or this top alone (TopCommand)
  msg.friction_law = friction_law(top);       // what the panel's law box shows
}

// The next entry of the array, reused from the last tick when there is one (its strings keep their storage); its
// name is copied only when another top had the slot (the order changes only when a top is added, killed or skipped).
top_sim::TopState& StateOutput::next_state(const NodeTop& top) {
  if (states_used_ == all_.states.size()) {
    all_.states.emplace_back();
    all_.names.emplace_back();
    named_.push_back(nullptr);
  }
  if (named_[states_used_] != &top) {
    all_.names[states_used_] = top.name();
    named_[states_used_] = &top;
  }
  return all_.states[states_used_++];
}

geometry_msgs::TransformStamped& StateOutput::next_transform() {
  if (tf_used_ == tf_msg_.transforms.size()) tf_msg_.transforms.emplace_back();
  return tf_msg_.transforms[tf_used_++];
}

// tf only when the top's time moved (a repeated stamp is dropped by listeners as TF_REPEATED_DATA); a top whose
// time stopped (its end, a pause) has its frames latched on /tf_static instead.
void StateOutput::add_transforms(NodeTop& top, const top_sim::TopPose& pose, const ros::Time& stamp) {
  if (!params_.publish_tf) return;
  if (!(stamp > top.output.last_tf_stamp)) return latch_frames(top, pose, stamp);
  const std::size_t i = tf_used_;  // two entries taken first: taking one may move the vector
  next_transform();
  next_transform();
  to_transforms(pose, stamp, top.frames(), tf_msg_.transforms[i], tf_msg_.transforms[i + 1]);
  if (markers_watched_) {  // only markers need them: thousands of unwatched tops send two transforms each
    to_contact_transform(pose, stamp, top.frames(), next_transform());
    add_grid_transform(top, pose, stamp);
  }
  top.output.last_tf_stamp = stamp;
}

// A listener started after a top's time stopped (rviz opened on an ended run) would never get its frames: /tf
// carries them only while time moves. So a stopped top's frames (body, contact, grid) go to /tf_static once, 1 ns
// after its last /tf stamp (a listener that has the last one takes them as new data, no TF_REPEATED_DATA); when its
// time moves on, /tf updates them as before.
void StateOutput::latch_frames(NodeTop& top, const top_sim::TopPose& pose, const ros::Time& stamp) {
  if (top.output.latched_stamp == stamp) return;
  top.output.latched_stamp = stamp;
  const ros::Time later = stamp + ros::Duration(0, 1);
  geometry_msgs::TransformStamped world_plane, plane_top, contact, grid;
  to_transforms(pose, later, top.frames(), world_plane, plane_top);
  to_contact_transform(pose, later, top.frames(), contact);
  to_grid_transform(pose, top.output.markers.grid_pitch(), later, top.frames(), grid);
  for (const geometry_msgs::TransformStamped* t : {&world_plane, &plane_top, &contact, &grid}) set_static(*t);
}

void StateOutput::set_static(const geometry_msgs::TransformStamped& t) {
  static_[t.child_frame_id] = t;
  static_changed_ = true;
}

void StateOutput::publish_static() {
  if (!static_changed_) return;
  static_changed_ = false;
  tf2_msgs::TFMessage all;
  all.transforms.reserve(static_.size());
  for (const auto& [child, t] : static_) all.transforms.push_back(t);
  tf_static_.publish(all);
}

// The grid frame moves in steps of the pitch: sent when it moved, else once a second (tf's lookups of the latest
// transform look back at most its 10 s cache). A sleeping top's tf is a fifth smaller.
void StateOutput::add_grid_transform(NodeTop& top, const top_sim::TopPose& pose, const ros::Time& stamp) {
  geometry_msgs::TransformStamped& grid = next_transform();
  to_grid_transform(pose, top.output.markers.grid_pitch(), stamp, top.frames(), grid);
  const Eigen::Vector3d at(grid.transform.translation.x, grid.transform.translation.y, grid.transform.translation.z);
  if (at == top.output.grid_at && (stamp - top.output.grid_stamp).toSec() < 1.0) {
    --tf_used_;  // not sent
    return;
  }
  top.output.grid_at = at;
  top.output.grid_stamp = stamp;
}

// The top ~follow names: a name asked for on the topic once it is known, else the one followed so far, else the
// launch-time top (the followed top was killed).
NodeTop& StateOutput::followed_top(TopSet& tops) {
  if (!follow_request_.empty()) {
    if (tops.find(follow_request_)) {
      follow_ = follow_request_;
      ROS_INFO("top_sim_node: %s follows top %s", params_.follow_frame.c_str(), follow_.c_str());
    } else {
      std::string known;
      for (const std::string& n : tops.names()) known += (known.empty() ? "" : ", ") + n;
      ROS_WARN("top_sim_node: follow = '%s': no such top (tops: %s); %s stays on %s", follow_request_.c_str(),
               known.c_str(), params_.follow_frame.c_str(), follow_.empty() ? tops.launch_top().name().c_str()
                                                                              : follow_.c_str());
    }
    follow_request_.clear();
  }
  NodeTop* top = follow_.empty() ? nullptr : tops.find(follow_);
  if (!top && !follow_.empty()) {
    ROS_WARN("top_sim_node: followed top %s is gone; %s follows top %s", follow_.c_str(),
             params_.follow_frame.c_str(), tops.launch_top().name().c_str());
    follow_.clear();
  }
  return top ? *top : tops.launch_top();
}

// follow: the followed top's contact frame under another name, on /tf_static (re-sent when the followed top changes):
// the camera's target moves with the contact frame, which tf carries every tick anyway.
void StateOutput::add_follow_transform(TopSet& tops) {
  NodeTop& top = followed_top(tops);
  if (!params_.publish_tf || params_.follow_frame.empty()) return;
  const top_sim::TopPose pose = top.sim().pose();
  if (!top_sim::all_finite(pose)) return;
  if (!markers_watched_ && top.output.last_tf_stamp > last_follow_stamp_)  // else add_transforms sent it
    to_contact_transform(pose, top.output.last_tf_stamp, top.frames(), next_transform());
  last_follow_stamp_ = top.output.last_tf_stamp;
  if (top.frames().contact == follow_parent_) return;
  follow_parent_ = top.frames().contact;
  geometry_msgs::TransformStamped t;
  t.header.stamp = top.output.last_tf_stamp;
  t.header.frame_id = follow_parent_;
  t.child_frame_id = params_.follow_frame;
  t.transform.rotation.w = 1.0;
  set_static(t);
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
  const bool resend = *marker_subscriptions_ != marker_subscriptions_seen_;
  marker_subscriptions_seen_ = *marker_subscriptions_;
  visualization_msgs::MarkerArray markers;
  MarkerTick tick;
  tick.wall = wall;
  tick.period = 1.0 / params_.marker_rate;
  tick.refresh = params_.marker_refresh;
  for (auto& t : tops) {
    TopOutput& out = t->output;
    out.trail.trim(params_.trail_seconds);
    const top_sim::Snapshot s = t->sim().snapshot();
    if (!top_sim::all_finite(s)) continue;
    if (resend) out.markers.resend_all();
    out.markers.follow_speed(top_sim_ros::speed_on_plane(s), params_.grid_pitch);
    tick.stamp = stamp(*t);
    out.markers.collect(s, t->sim().model().top, out.trail, t->frames(), style(*t), t->prefix(), tick, markers);
  }
  markers_.publish(markers);
  last_marker_wall_ = wall;
}

void StateOutput::publish_paths(TopSet& tops, double wall) {
  if (wall - last_path_wall_ < 1.0 / params_.path_rate) return;
  for (auto& t : tops) {
    TopOutput& out = t->output;
    if (out.path_readers <= 0 || !out.path) continue;
    out.trail.trim(params_.trail_seconds);
    out.trail.to_path(t->frames().plane, path_);
    path_.header.stamp = stamp(*t);
    path_.header.frame_id = t->frames().plane;
    out.path.publish(path_);  // serialised now: path_ serves the next top
  }
  last_path_wall_ = wall;
}

void StateOutput::publish_lcm(const top_sim::Snapshot& s, double achieved_factor, double requested_factor,
                              bool paused, const char* friction_law) {
#ifdef TOP_SIM_HAVE_LCM
  if (lcm_ && !lcm_->publish(s, {achieved_factor, requested_factor, paused, friction_law}) && !lcm_send_failed_) {
    ROS_ERROR("top_sim_node: LCM publish on %s failed (reported once)", lcm_->channel().c_str());
    lcm_send_failed_ = true;
  }
#else
  (void)s;
  (void)achieved_factor;
  (void)requested_factor;
  (void)paused;
  (void)friction_law;
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
