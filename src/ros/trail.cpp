#include "trail.hpp"

#include <algorithm>
#include <utility>

namespace top_sim_ros {

std::vector<Trail::Point> Trail::storage() {
  if (spare_.empty()) {
    std::vector<Point> fresh;
    fresh.reserve(kChunkPoints);
    return fresh;
  }
  std::vector<Point> reused = std::move(spare_.back());
  spare_.pop_back();
  reused.clear();
  return reused;
}

void Trail::open_chunk() {
  Chunk c;
  c.id = next_id_++;
  c.version = next_version_++;
  c.points = storage();
  if (!chunks_.empty()) {  // the new chunk starts where the closed one ends
    c.points.push_back(chunks_.back().points.back());
    ++points_;
  }
  chunks_.push_back(std::move(c));
}

void Trail::add(const Eigen::Vector3d& p, const ros::Time& stamp, double resolution, std::size_t length) {
  if (!chunks_.empty() && resolution > 0.0 && (p - newest_).norm() < resolution) return;
  if (chunks_.empty() || chunks_.back().points.size() >= kChunkPoints) open_chunk();
  Chunk& head = chunks_.back();
  head.points.push_back({stamp, p});
  head.version = next_version_++;
  ++points_;
  newest_ = p;
  if (points_ > length) merge_oldest();
}

// The oldest pair of neighbouring closed chunks of one level (else the two oldest) becomes one chunk of the next
// level: the first's start, every other point after it, the second's end (so it still joins its neighbours).
void Trail::merge_oldest() {
  if (chunks_.size() < 3) return;  // two closed chunks at least, the open one is never merged
  std::size_t i = 0;
  for (std::size_t k = 0; k + 2 < chunks_.size(); ++k)
    if (chunks_[k].level == chunks_[k + 1].level) {
      i = k;
      break;
    }
  Chunk &a = chunks_[i], &b = chunks_[i + 1];
  std::vector<Point> joined = storage();
  joined.push_back(a.points.front());
  const std::size_t na = a.points.size(), n = na + b.points.size() - 1;  // b's first point is a's last
  auto at = [&](std::size_t k) -> const Point& { return k < na ? a.points[k] : b.points[k - na + 1]; };
  for (std::size_t k = 2; k + 1 < n; k += 2) joined.push_back(at(k));
  joined.push_back(at(n - 1));
  points_ -= a.points.size() + b.points.size() - joined.size();
  spare_.push_back(std::move(a.points));
  spare_.push_back(std::move(b.points));
  a.points = std::move(joined);
  a.level = std::max(a.level, b.level) + 1;
  a.version = next_version_++;
  chunks_.erase(chunks_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
}

void Trail::trim(double seconds) {
  if (chunks_.empty()) return;
  const double keep_from = chunks_.back().points.back().stamp.toSec() - seconds;
  while (chunks_.size() > 1 && chunks_.front().points.back().stamp.toSec() < keep_from) {
    points_ -= chunks_.front().points.size();
    spare_.push_back(std::move(chunks_.front().points));
    chunks_.pop_front();
  }
}

void Trail::clear() {
  for (Chunk& c : chunks_) spare_.push_back(std::move(c.points));
  chunks_.clear();
  points_ = 0;
}

void Trail::to_path(const std::string& plane_frame, nav_msgs::Path& out) const {
  out.poses.clear();
  out.poses.reserve(points_);
  for (std::size_t c = 0; c < chunks_.size(); ++c) {
    const std::vector<Point>& pts = chunks_[c].points;
    for (std::size_t i = c == 0 ? 0 : 1; i < pts.size(); ++i) {  // a chunk's first point is its predecessor's last
      geometry_msgs::PoseStamped ps;
      ps.header.stamp = pts[i].stamp;
      ps.header.frame_id = plane_frame;
      ps.pose.position.x = pts[i].position.x();
      ps.pose.position.y = pts[i].position.y();
      ps.pose.position.z = pts[i].position.z();
      ps.pose.orientation.w = 1.0;
      out.poses.push_back(std::move(ps));
    }
  }
}

}  // namespace top_sim_ros
