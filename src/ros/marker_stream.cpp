#include "marker_stream.hpp"

#include <algorithm>
#include <cmath>

namespace top_sim_ros {

namespace {

void add_prefixed(visualization_msgs::Marker m, const std::string& prefix, visualization_msgs::MarkerArray& out) {
  m.ns = prefix + m.ns;
  out.markers.push_back(std::move(m));
}

// Drawn the same: the same text and colour, every point within 0.1 mm (a marker tick's change of a sleeping top's
// arrows is far below a pixel).
bool looks_same(const visualization_msgs::Marker& a, const visualization_msgs::Marker& b) {
  constexpr double kSamePoint = 1e-4;  // [m]
  if (a.text != b.text || a.color.r != b.color.r || a.color.g != b.color.g || a.color.b != b.color.b ||
      a.points.size() != b.points.size() || a.pose.position.z != b.pose.position.z)
    return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (std::abs(a.points[i].x - b.points[i].x) > kSamePoint || std::abs(a.points[i].y - b.points[i].y) > kSamePoint ||
        std::abs(a.points[i].z - b.points[i].z) > kSamePoint)
      return false;
  return true;
}

visualization_msgs::Marker deletion(const std::string& ns, int id, const std::string& frame,
                                    const ros::Time& stamp) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.action = visualization_msgs::Marker::DELETE;
  return m;
}

}  // namespace

void MarkerStream::collect(const top_sim::Snapshot& s, const top_sim::Top& top, const Trail& trail,
                           const Frames& frames, const MarkerStyle& style, const std::string& prefix,
                           const MarkerTick& tick, visualization_msgs::MarkerArray& out) {
  FixedKey key{body_colour(s, style.color_by), style.grid_pitch, top.mass, top.inertia_axial, top.tip_radius,
               top.com_offset};
  if (shapes_.active) key.touching = s.touching, key.rim_up = s.figure_axis.z() >= 0.0;
  visualization_msgs::MarkerArray drawn;
  if (!(key == fixed_sent_) || tick.wall - fixed_wall_ >= tick.refresh) {
    fixed_markers(s, top, shapes_, tick.stamp, frames, style, drawn);
    fixed_sent_ = key;
    fixed_wall_ = tick.wall;
  }
  for (auto& m : drawn.markers) add_prefixed(std::move(m), prefix, out);
  collect_moving(s, top, frames, style, prefix, tick, out);
  collect_trail(trail, frames, prefix, tick, out);
  // Attached when the top would leave the head's end visibly behind before the next tick (2 cm); a slower top's head
  // stays in the plane, joined to the closed chunks.
  constexpr double kVisibleGap = 0.02;  // [m]
  const bool attached = speed_on_plane(s) * tick.period > kVisibleGap;
  const visualization_msgs::Marker head = trail_head_marker(trail, s.contact_point, tick.stamp, frames, attached);
  if (head.action == visualization_msgs::Marker::ADD || head_sent_) add_prefixed(head, prefix, out);
  head_sent_ = head.action == visualization_msgs::Marker::ADD;
}

// The arrows and the label when they look different from what was sent, else at the refresh.
void MarkerStream::collect_moving(const top_sim::Snapshot& s, const top_sim::Top& top, const Frames& frames,
                                  const MarkerStyle& style, const std::string& prefix, const MarkerTick& tick,
                                  visualization_msgs::MarkerArray& out) {
  visualization_msgs::MarkerArray drawn;
  moving_markers(s, top, shapes_, tick.stamp, frames, style, drawn);
  const bool refresh = tick.wall - moving_wall_ >= tick.refresh;
  if (refresh) moving_wall_ = tick.wall;
  moving_sent_.resize(drawn.markers.size());
  for (std::size_t i = 0; i < drawn.markers.size(); ++i) {
    if (!refresh && looks_same(drawn.markers[i], moving_sent_[i])) continue;
    moving_sent_[i] = drawn.markers[i];
    add_prefixed(std::move(drawn.markers[i]), prefix, out);
  }
}

// New and changed closed chunks, DELETEs of the chunks gone, and a share of the rest (all within `refresh`).
void MarkerStream::collect_trail(const Trail& trail, const Frames& frames, const std::string& prefix,
                                 const MarkerTick& tick, visualization_msgs::MarkerArray& out) {
  const auto& chunks = trail.chunks();
  const std::size_t closed = chunks.empty() ? 0 : chunks.size() - 1;
  // Every closed chunk again within `refresh`: a share per tick, the fraction carried to the next tick.
  refresh_credit_ = std::min(refresh_credit_ + closed * tick.period / tick.refresh, static_cast<double>(closed));
  const auto share = static_cast<std::size_t>(refresh_credit_);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> sent;
  sent.reserve(closed);
  auto was = chunks_sent_.begin();
  std::size_t refreshed = 0;
  for (std::size_t i = 0; i < closed; ++i) {
    const Trail::Chunk& c = chunks[i];
    for (; was != chunks_sent_.end() && was->first < c.id; ++was)  // sent, now gone
      out.markers.push_back(deletion(prefix + "trail", static_cast<int>(was->first), frames.plane, tick.stamp));
    const bool listed = was != chunks_sent_.end() && was->first == c.id;
    const bool known = listed && was->second == c.version;
    if (listed) ++was;
    const bool due = c.id >= refresh_from_ && refreshed < share;
    if (!known || due) {
      add_prefixed(trail_chunk_marker(c, tick.stamp, frames.plane), prefix, out);
      if (known) ++refreshed, refresh_from_ = c.id + 1;
    }
    sent.emplace_back(c.id, c.version);
  }
  for (; was != chunks_sent_.end(); ++was)  // gone: the trail was cleared, or the chunk merged into its neighbour
    out.markers.push_back(deletion(prefix + "trail", static_cast<int>(was->first), frames.plane, tick.stamp));
  refresh_credit_ -= refreshed;
  if (refreshed < share || closed == 0 || refresh_from_ > chunks[closed - 1].id) refresh_from_ = 0;  // round over
  chunks_sent_ = std::move(sent);
}

void MarkerStream::remove_all(const top_sim::Snapshot& s, const top_sim::Top& top, const Frames& frames,
                              const MarkerStyle& style, const std::string& prefix, const ros::Time& stamp,
                              visualization_msgs::MarkerArray& out) {
  visualization_msgs::MarkerArray drawn;
  to_markers(s, top, shapes_, stamp, frames, style, drawn);
  for (auto& m : drawn.markers) out.markers.push_back(deletion(prefix + m.ns, m.id, m.header.frame_id, stamp));
  for (const auto& [id, version] : chunks_sent_)
    out.markers.push_back(deletion(prefix + "trail", static_cast<int>(id), frames.plane, stamp));
  add_prefixed(trail_head_marker(Trail(), Eigen::Vector3d::Zero(), stamp, frames, false), prefix, out);  // DELETE
  chunks_sent_.clear();
}

void MarkerStream::resend_all() {
  fixed_wall_ = moving_wall_ = -std::numeric_limits<double>::infinity();
  for (auto& c : chunks_sent_) c.second = 0;  // versions start at 1: every chunk differs
}

}  // namespace top_sim_ros
