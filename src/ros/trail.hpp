// The contact-point trail of one top (docs/ros.md, ~path and the "trail" markers), kept in chunks of a few dozen
// points: a chunk, once closed, does not change until it is merged or trimmed, so rviz and a bag get each point
// once (in its chunk's marker) instead of the whole trail at every marker tick.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
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
  struct Chunk {
    std::uint64_t id = 0;       // unique within the trail, increasing from the oldest chunk to the newest
    std::uint64_t version = 0;  // changes whenever the chunk's points change
    int level = 0;              // how often its points were halved by merges (0: every recorded point)
    std::vector<Point> points;  // a chunk starts at its predecessor's last point, so the chunks join up
  };
  static constexpr std::size_t kChunkPoints = 16;  // points a chunk closes at

  // Records p when it is `resolution` or more from the newest point. Beyond `length` points the two oldest chunks
  // of one level are merged into one with every other point (the trail still covers its time, its old part
  // coarser; the newest chunks keep every point).
  void add(const Eigen::Vector3d& p, const ros::Time& stamp, double resolution, std::size_t length);
  // Chunks whose newest point is older than `seconds` before the trail's newest go (before each publication): the
  // trail covers at least `seconds`, and at most one chunk more.
  void trim(double seconds);
  void clear();
  bool empty() const { return chunks_.empty(); }
  std::size_t size() const { return points_; }  // points held, the joints counted twice
  // Oldest first; the last chunk is open (it grows until kChunkPoints), every other one is closed.
  const std::deque<Chunk>& chunks() const { return chunks_; }
  // The poses of ~path (frame `plane_frame`, identity orientation), each point once; the header is the caller's.
  void to_path(const std::string& plane_frame, nav_msgs::Path& out) const;

 private:
  std::vector<Point> storage();  // an empty vector with room for a chunk, reused when one is spare
  void open_chunk();
  void merge_oldest();
  std::deque<Chunk> chunks_;
  std::vector<std::vector<Point>> spare_;  // storage of chunks that went, reused (no allocation in steady state)
  std::size_t points_ = 0;
  std::uint64_t next_id_ = 1, next_version_ = 1;
  // The newest point's position, next to the top's other per-tick data: the check of a top that has not moved
  // does not touch the chunks (thousands of trails do not stay in the cache).
  Eigen::Vector3d newest_ = Eigen::Vector3d::Zero();
};

}  // namespace top_sim_ros
