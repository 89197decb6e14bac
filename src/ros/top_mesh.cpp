#include "top_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace top_sim_ros {

namespace {

// A tippe top (f < 0): the body is its sphere, centred |f| above the centre of mass (at z = -f); the cap round its
// pole along +f_hat is the stem's place, so that turning over shows without anything outside the sphere.
TopShape ball_shape(const top_sim::Top& top) {
  const double f = top.com_offset, R = top.tip_radius;
  TopShape s;
  s.body_radius = R;
  s.stem_radius = 0.3 * R;
  const double foot = std::asin(std::sqrt(R * R - s.stem_radius * s.stem_radius) / R);  // the cap's edge
  s.stem_bottom = -f + R * std::sin(foot);
  s.stem_top = -f + R;
  s.rim_height = 2.0 * R;
  constexpr int kArc = 16;  // points on the meridian from the bottom pole to the cap's edge
  for (int i = 0; i <= kArc; ++i) {
    const double a = -0.5 * M_PI + (foot + 0.5 * M_PI) * i / kArc;
    s.profile.emplace_back(R * std::cos(a), -f + R * std::sin(a));
  }
  s.profile.front().x() = 0.0;  // exactly on the axis: a fan, no degenerate triangles
  constexpr int kCapArc = 4;
  for (int i = 0; i <= kCapArc; ++i) {
    const double a = foot + (0.5 * M_PI - foot) * i / kCapArc;
    s.cap.emplace_back(R * std::cos(a), -f + R * std::sin(a));
  }
  s.cap.back().x() = 0.0;
  return s;
}

}  // namespace

TopShape top_shape(const top_sim::Top& top) {
  if (top.com_offset < 0.0) return ball_shape(top);
  const double f = top.com_offset, R = top.tip_radius;
  TopShape s;
  s.body_radius = std::sqrt(2.0 * top.inertia_axial / top.mass);
  const double rb = s.body_radius, t = std::max(0.25 * rb, 2.0 * R);
  s.rim_height = t;
  s.stem_radius = std::min(std::max(0.12 * rb, 0.75 * R), 0.5 * rb);
  s.stem_bottom = t;
  s.stem_top = t + std::max(f, 0.5 * rb);
  // The cone's foot stays inside the tip sphere and well inside the rim, so the profile never crosses itself.
  const double foot = std::min(R, 0.5 * rb);
  s.profile = {{0.0, -f}, {foot, -f}, {rb, -0.5 * t}, {rb, 0.5 * t}, {s.stem_radius, t}, {0.0, t}};
  return s;
}

std::vector<Eigen::Vector3d> revolve(const std::vector<Eigen::Vector2d>& profile, int segments, double start,
                                     double sweep) {
  const bool full_turn = sweep >= 2.0 * M_PI;
  // The seam of a full turn reuses the angle of step 0 so both sides share bit-identical points.
  auto at = [&](const Eigen::Vector2d& p, int j) {
    const double a = start + sweep * (full_turn ? j % segments : j) / segments;
    return Eigen::Vector3d(p.x() * std::cos(a), p.x() * std::sin(a), p.y());
  };
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    for (int j = 0; j < segments; ++j) {
      const Eigen::Vector3d a = at(profile[i], j), b = at(profile[i], j + 1);
      const Eigen::Vector3d c = at(profile[i + 1], j + 1), d = at(profile[i + 1], j);
      if (profile[i].x() > 0.0) out.insert(out.end(), {a, b, c});      // a == b on the axis
      if (profile[i + 1].x() > 0.0) out.insert(out.end(), {a, c, d});  // c == d on the axis
    }
  }
  return out;
}

std::vector<Eigen::Vector2d> raised_profile(const std::vector<Eigen::Vector2d>& profile, double distance) {
  // Outward normal of a counter-clockwise edge (dr, dz) is (dz, -dr).
  auto normal = [&](std::size_t i) {
    const Eigen::Vector2d d = profile[i + 1] - profile[i];
    return Eigen::Vector2d(d.y(), -d.x()).normalized();
  };
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 1; i + 1 < profile.size(); ++i) {
    if (profile[i].x() <= 0.0) continue;
    out.push_back(profile[i] + distance * (normal(i - 1) + normal(i)).normalized());
  }
  return out;
}

}  // namespace top_sim_ros
