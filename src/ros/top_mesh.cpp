#include "top_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

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

namespace {

constexpr int kSphereArc = 16;  // points on a sphere's meridian from pole to pole

// A sphere's meridian from its bottom pole to its top pole (counter-clockwise in the (r, z) half-plane).
std::vector<Eigen::Vector2d> sphere_profile(const top_sim::ContactShape& s) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i <= kSphereArc; ++i) {
    const double a = -0.5 * M_PI + M_PI * i / kSphereArc;
    p.emplace_back(s.radius * std::cos(a), s.offset + s.radius * std::sin(a));
  }
  p.front().x() = p.back().x() = 0.0;  // exactly on the axis: fans, no degenerate triangles
  return p;
}

// The z range of a rim's drawn disc: from its circle, its thickness up or down.
std::pair<double, double> rim_faces(const top_sim::ContactShape& s, double thickness, bool up) {
  return up ? std::make_pair(s.offset, s.offset + thickness) : std::make_pair(s.offset - thickness, s.offset);
}

void append(std::vector<Eigen::Vector3d>& to, const std::vector<Eigen::Vector3d>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

// The profile the stripe is painted on: the widest shape's meridian, or a rim's edge with the outer half of its
// faces (a disc's edge alone is too thin to see turning).
std::vector<Eigen::Vector2d> stripe_profile(const top_sim::ContactShape& s, std::pair<double, double> z) {
  if (s.kind == top_sim::ShapeKind::sphere) return sphere_profile(s);
  const double r = s.radius;
  return {{0.0, z.first}, {0.5 * r, z.first}, {r, z.first}, {r, z.second}, {0.5 * r, z.second}, {0.0, z.second}};
}

}  // namespace

double rim_thickness(const top_sim::Top& top, const top_sim::ShapeSet& shapes, std::size_t i) {
  const double rho = shapes.shape[i].radius;
  if (shapes.count == 1) {
    const double t2 = 12.0 * (top.inertia_transverse / top.mass - 0.25 * rho * rho);
    if (t2 > 0.0 && std::isfinite(t2)) return std::sqrt(t2);
  }
  return kThinRim * rho;
}

double reach_from_contact(const top_sim::Top& top, const top_sim::ShapeSet& shapes) {
  if (shapes.active) return 2.0 * shape_reach(top, shapes);
  return top_shape(top).body_radius + std::abs(top.com_offset) + top.tip_radius;
}

double shape_reach(const top_sim::Top& top, const top_sim::ShapeSet& shapes) {
  double reach = 0.0;
  for (std::size_t i = 0; i < shapes.count; ++i) {
    const top_sim::ContactShape& s = shapes.shape[i];
    const double far = s.kind == top_sim::ShapeKind::sphere
                           ? std::abs(s.offset) + s.radius
                           : std::hypot(s.radius, std::abs(s.offset) + rim_thickness(top, shapes, i));
    reach = std::max(reach, far);
  }
  return reach;
}

ShapeMesh shape_mesh(const top_sim::Top& top, const top_sim::ShapeSet& shapes, std::uint32_t touching, bool rim_up,
                     int segments, double stripe_width, double stripe_raise) {
  ShapeMesh mesh;
  std::vector<std::size_t> order(shapes.count);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return shapes.shape[a].offset < shapes.shape[b].offset; });
  std::size_t widest = 0;
  std::pair<double, double> widest_z;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    const top_sim::ContactShape& s = shapes.shape[i];
    const bool touches = (touching >> i) & 1u;
    std::pair<double, double> z{s.offset - s.radius, s.offset + s.radius};
    if (s.kind == top_sim::ShapeKind::sphere) {
      append(touches ? mesh.touching : mesh.body, revolve(sphere_profile(s), segments, 0.0, 2.0 * M_PI));
    } else {
      const bool up = shapes.count == 1 ? rim_up : k > 0;
      z = rim_faces(s, rim_thickness(top, shapes, i), up);
      const double r = s.radius, tyre = (1.0 - kTyre) * r;
      append(mesh.body, revolve({{0.0, z.first}, {tyre, z.first}}, segments, 0.0, 2.0 * M_PI));
      append(touches ? mesh.touching : mesh.body,
             revolve({{tyre, z.first}, {r, z.first}, {r, z.second}, {tyre, z.second}}, segments, 0.0, 2.0 * M_PI));
      append(mesh.body, revolve({{tyre, z.second}, {0.0, z.second}}, segments, 0.0, 2.0 * M_PI));
    }
    if (s.radius > shapes.shape[widest].radius || k == 0) widest = i, widest_z = z;
    if (k == 0) continue;
    const top_sim::ContactShape& below = shapes.shape[order[k - 1]];
    if (s.offset > below.offset)  // the cone between the widest circles: each shape's circle at its offset
      append(mesh.body, revolve({{below.radius, below.offset}, {s.radius, s.offset}}, segments, 0.0, 2.0 * M_PI));
  }
  const top_sim::ContactShape& w = shapes.shape[widest];
  const int stripe_segments = std::max(1, static_cast<int>(std::ceil(stripe_width * segments / (2.0 * M_PI))));
  mesh.stripe = revolve(raised_profile(stripe_profile(w, widest_z), stripe_raise * w.radius), stripe_segments,
                        -0.5 * stripe_width, stripe_width);
  return mesh;
}

}  // namespace top_sim_ros
