// The contact-point trail of one top (docs/ros.md, ~path and the "trail" marker): kept as bare stamped points and
// built into a nav_msgs::Path only when published, so recording it every tick for thousands of tops costs a
// compare and, now and then, 32 bytes (a PoseStamped with its frame name is over 100).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nav_msgs/Path.h>
#include <ros/time.h>

namespace top_sim_ros {

class Trail {
 public:
  struct Point {
    ros::Time stamp;
    Eigen::Vector3d position;  // plane frame [m]
  };

  // Records p when it is `resolution` or more from the newest point; beyond `length` points every other point of
  // the older half goes (the trail still covers its time, its old part coarser).
  void add(const Eigen::Vector3d& p, const ros::Time& stamp, double resolution, std::size_t length);
  // Room for the most points the trail holds, its pages mapped now (at the top's spawn) instead of one page fault
  // per 128 points in the top's first minute of ticks (3 % of the node with 1000 tops).
  void reserve(std::size_t length);
  // Points older than `seconds` before the newest go (before each publication).
  void trim(double seconds);
  void clear() { points_.clear(); }
  const std::vector<Point>& points() const { return points_; }
  // The poses of ~path (frame `plane_frame`, identity orientation); the header is the caller's.
  void to_path(const std::string& plane_frame, nav_msgs::Path& out) const;

 private:
  void thin();
  std::vector<Point> points_;
  // The newest point's position, next to the top's other per-tick data: the check of a top that has not moved
  // does not touch the points (thousands of trails do not stay in the cache). Trimming and thinning keep it.
  Eigen::Vector3d newest_ = Eigen::Vector3d::Zero();
};

}  // namespace top_sim_ros
