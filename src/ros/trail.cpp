#include "trail.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>

namespace top_sim_ros {

namespace {

// Asks the kernel to map the whole pages inside [begin, end) now; a kernel without MADV_POPULATE_WRITE (before
// Linux 5.14) refuses and the pages are faulted in as the trail fills, as before.
void populate(const void* begin, const void* end) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) / page * page;
  const std::uintptr_t last = reinterpret_cast<std::uintptr_t>(end) / page * page;
#ifdef MADV_POPULATE_WRITE
  if (last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
#else
  (void)first;
  (void)last;
#endif
}

}  // namespace

// Room for the most the trail holds (up to kReserveMost), reserved at once: growing by doubling copied a trail of
// thousands of points into fresh pages several times in its first seconds; a huge path_length reserves no more.
void Trail::reserve(std::size_t length) {
  constexpr std::size_t kReserveMost = 8192;
  if (points_.capacity() > 0) return;
  points_.reserve(std::min(length + 1, kReserveMost));
  populate(points_.data(), points_.data() + points_.capacity());
}

void Trail::add(const Eigen::Vector3d& p, const ros::Time& stamp, double resolution, std::size_t length) {
  if (!points_.empty() && resolution > 0.0 && (p - newest_).norm() < resolution) return;
  reserve(length);  // a trail that was not reserved at its top's spawn
  points_.push_back({stamp, p});
  // The line after the one just written, asked for now: the next adds write there, and with a thousand trails a
  // line first written then comes from memory (Trail::add was 5 % of the node at 1000 tops x 200 Hz). A hint: an
  // address past the storage is not read.
  const std::uintptr_t next_line = reinterpret_cast<std::uintptr_t>(points_.data() + points_.size()) + 64;
  __builtin_prefetch(reinterpret_cast<const void*>(next_line), 1);
  newest_ = p;
  if (points_.size() > length) thin();
}

// The oldest point stays (the trail's start); of the rest of the older half, every other one.
void Trail::thin() {
  const std::size_t half = points_.size() / 2;
  std::size_t kept = 1;
  for (std::size_t i = 1; i < half; ++i)
    if (i % 2 == 0) points_[kept++] = points_[i];
  points_.erase(points_.begin() + kept, points_.begin() + half);
}

void Trail::trim(double seconds) {
  if (points_.empty()) return;
  const double keep_from = points_.back().stamp.toSec() - seconds;
  std::size_t stale = 0;
  while (stale + 1 < points_.size() && points_[stale].stamp.toSec() < keep_from) ++stale;
  if (stale > 0) points_.erase(points_.begin(), points_.begin() + stale);
}

void Trail::to_path(const std::string& plane_frame, nav_msgs::Path& out) const {
  out.poses.resize(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    geometry_msgs::PoseStamped& ps = out.poses[i];
    ps.header.stamp = points_[i].stamp;
    ps.header.frame_id = plane_frame;
    ps.pose.position.x = points_[i].position.x();
    ps.pose.position.y = points_[i].position.y();
    ps.pose.position.z = points_[i].position.z();
    ps.pose.orientation = geometry_msgs::Quaternion();
    ps.pose.orientation.w = 1.0;
  }
}

}  // namespace top_sim_ros
