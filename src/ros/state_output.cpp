#include "state_output.hpp"

#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <boost/function.hpp>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>
#include <visualization_msgs/MarkerArray.h>

#include "markers.hpp"

#include "top_sim/TopState.h"
#include "top_sim/TopStateArray.h"

namespace top_sim_ros {

StateOutput::StateOutput(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParameters& params, double stamp_origin)
    : params_(params), stamp_origin_(stamp_origin), follow_request_(params.follow) {
  markers_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 2);
  const boost::function<void(const std_msgs::String::ConstPtr&)> follow = [this](const std_msgs::String::ConstPtr& m) {
    on_follow(m->data);
  };
  follow_sub_ = pnh.subscribe<std_msgs::String>("follow", 1, follow);
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

// Marker namespaces carry the top's prefix, so rviz keeps one set per top ("" for the launch-time top).
void StateOutput::add_markers(const NodeTop& top, const top_sim::Snapshot& s, const ros::Time& stamp,
                              visualization_msgs::MarkerArray& out) const {
  MarkerStyle style;
  style.name = top.name();
  style.color_by = params_.color_by;
  style.grid_pitch = params_.grid_pitch;
  style.grid_cells = params_.grid_cells;
  visualization_msgs::MarkerArray one;
  to_markers(s, top.sim().model().top, stamp, top.frames(), style, one);
  one.markers.push_back(trail_marker(top.output.trail, stamp, top.frames().plane));
  for (auto& m : one.markers) {
    m.ns = top.prefix() + m.ns;
    out.markers.push_back(std::move(m));
  }
}

void StateOutput::close(NodeTop& top) {
  visualization_msgs::MarkerArray gone;
  add_markers(top, top.sim().snapshot(), stamp(top), gone);
  for (auto& m : gone.markers) m.action = visualization_msgs::Marker::DELETE;
  markers_.publish(gone);
}

void StateOutput::publish(TopSet& tops, double wall, bool paused, double requested_factor) {
  const bool array = states_.getNumSubscribers() > 0;
  markers_watched_ = markers_.getNumSubscribers() > 0;
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
    if (top.launch_top()) publish_lcm(s, top.pacer().achieved_factor(), requested_factor, paused);
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
  add_follow_transform(tops, tf);
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
  if (markers_watched_) {  // only markers need it: thousands of unwatched tops send two transforms each
    to_contact_transform(s, stamp, top.frames(), pt);
    tf.push_back(pt);
    to_grid_transform(s, params_.grid_pitch, stamp, top.frames(), pt);
    tf.push_back(pt);
  }
  top.output.last_tf_stamp = stamp;
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

// follow: at the followed top's contact point with its plane's axes, stamped as that top's tf.
void StateOutput::add_follow_transform(TopSet& tops, std::vector<geometry_msgs::TransformStamped>& tf) {
  NodeTop& top = followed_top(tops);
  if (!params_.publish_tf || params_.follow_frame.empty()) return;
  const top_sim::Snapshot s = top.sim().snapshot();
  if (!top_sim::all_finite(s)) return;
  Frames frames = top.frames();
  frames.contact = params_.follow_frame;
  geometry_msgs::TransformStamped follow;
  to_contact_transform(s, top.output.last_tf_stamp, frames, follow);
  if (!(follow.header.stamp > last_follow_stamp_)) return;  // a repeated stamp is TF_REPEATED_DATA
  last_follow_stamp_ = follow.header.stamp;
  tf.push_back(follow);
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
    trim_trail(t->output.trail);
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

// Contact-point trail: a pose each time the point has moved path_resolution, over the last trail_seconds.
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
  if (path.poses.size() > static_cast<std::size_t>(params_.path_length)) thin_trail(path);
}

// Over path_length poses: every other pose of the older half goes, so the trail still covers trail_seconds, its
// old part coarser (a fast top's trail would otherwise cover a fraction of a second).
void StateOutput::thin_trail(nav_msgs::Path& path) const {
  auto& poses = path.poses;
  const std::size_t half = poses.size() / 2;
  std::size_t kept = 1;  // the oldest pose stays: the trail's start
  for (std::size_t i = 1; i < half; ++i)
    if (i % 2 == 0) poses[kept++] = std::move(poses[i]);
  poses.erase(poses.begin() + kept, poses.begin() + half);
}

// Poses older than trail_seconds before the newest go (before each publication; a pose's stamp is its time).
void StateOutput::trim_trail(nav_msgs::Path& path) const {
  auto& poses = path.poses;
  if (poses.empty()) return;
  const ros::Time newest = poses.back().header.stamp;
  const double keep_from = newest.toSec() - params_.trail_seconds;
  std::size_t stale = 0;
  while (stale + 1 < poses.size() && poses[stale].header.stamp.toSec() < keep_from) ++stale;
  if (stale > 0) poses.erase(poses.begin(), poses.begin() + stale);
}

void StateOutput::publish_lcm(const top_sim::Snapshot& s, double achieved_factor, double requested_factor,
                              bool paused) {
#ifdef TOP_SIM_HAVE_LCM
  if (lcm_ && !lcm_->publish(s, {achieved_factor, requested_factor, paused}) && !lcm_send_failed_) {
    ROS_ERROR("top_sim_node: LCM publish on %s failed (reported once)", lcm_->channel().c_str());
    lcm_send_failed_ = true;
  }
#else
  (void)s;
  (void)achieved_factor;
  (void)requested_factor;
  (void)paused;
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
