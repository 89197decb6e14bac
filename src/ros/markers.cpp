#include "markers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "top_mesh.hpp"

namespace top_sim_ros {

namespace {

// Marker ids, one per kind and fixed: an update replaces the marker of the same (ns, id) in rviz.
enum MarkerId : int {
  kPlaneMarker = 0,
  kTipMarker,
  kBodyMarker,
  kStripeMarker,
  kStemMarker,
  kSpinMarker,
  kVelocityMarker,
  kLabelMarker,
  kGridMarker,
  kTrailMarker,
};

constexpr int kBodySegments = 32;        // facets round the body: smooth at rviz's usual distances
constexpr double kStripeWidth = 0.5;     // [rad] of the body's circumference painted, centred on body x
constexpr double kStripeRaise = 0.02;    // stripe height above the surface, relative to the body radius

visualization_msgs::Marker marker(const std::string& frame, const ros::Time& stamp, const std::string& ns, int id,
                                  int type, Rgb c) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.color.r = c.r; m.color.g = c.g; m.color.b = c.b; m.color.a = 1.0f;
  m.frame_locked = true;  // rviz re-reads the frame's tf every frame: the marker moves at the tf rate
  return m;
}

// Arrow length saturating at `max_len`: direction matters more than size on screen.
double arrow_length(double value, double reference, double max_len) {
  const double a = std::abs(value);
  return max_len * a / (a + reference);
}

// The grid and a translucent square under it, in the grid frame (the contact point snapped to the pitch, moved by
// tf at the tf rate): the lines keep their place on the plane while the square follows the top at any distance
// and speed.
void add_plane(const Frames& frames, const ros::Time& stamp, const MarkerStyle& style,
               visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  const double pitch = style.grid_pitch, half = 0.5 * style.grid_cells * pitch;
  Marker plane = marker(frames.grid, stamp, "plane", kPlaneMarker, Marker::CUBE, {0.75f, 0.78f, 0.85f});
  plane.pose.position.z = -0.001;
  plane.scale.x = plane.scale.y = 2.0 * half;
  plane.scale.z = 0.001;
  plane.color.a = 0.35f;
  out.markers.push_back(plane);

  Marker grid = marker(frames.grid, stamp, "grid", kGridMarker, Marker::LINE_LIST, {0.6f, 0.6f, 0.65f});
  grid.pose.position = plane.pose.position;
  grid.pose.position.z = -0.0004;
  grid.scale.x = 0.04 * pitch;  // line width
  grid.color.a = 0.6f;
  for (int i = 0; i <= style.grid_cells; ++i) {
    const double u = -half + i * pitch;
    grid.points.push_back(point(Eigen::Vector3d(u, -half, 0.0)));
    grid.points.push_back(point(Eigen::Vector3d(u, half, 0.0)));
    grid.points.push_back(point(Eigen::Vector3d(-half, u, 0.0)));
    grid.points.push_back(point(Eigen::Vector3d(half, u, 0.0)));
  }
  out.markers.push_back(grid);
}

// Body of revolution, a stripe fixed to the body (it turns with the spin phase that tf carries in the top frame)
// and the stem; all in the top frame.
void add_body(const TopShape& shape, Rgb colour, const std::string& frame, const ros::Time& stamp,
              visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  Marker body = marker(frame, stamp, "body", kBodyMarker, Marker::TRIANGLE_LIST, colour);
  body.scale.x = body.scale.y = body.scale.z = 1.0;  // TRIANGLE_LIST points are multiplied by the scale
  for (const Eigen::Vector3d& p : revolve(shape.profile, kBodySegments, 0.0, 2.0 * M_PI))
    body.points.push_back(point(p));
  out.markers.push_back(body);

  Marker stripe = marker(frame, stamp, "stripe", kStripeMarker, Marker::TRIANGLE_LIST, {1.0f, 0.5f, 0.0f});
  stripe.scale = body.scale;
  const int stripe_segments = std::max(1, static_cast<int>(std::ceil(kStripeWidth * kBodySegments / (2.0 * M_PI))));
  for (const Eigen::Vector3d& p : revolve(raised_profile(shape.profile, kStripeRaise * shape.body_radius),
                                          stripe_segments, -0.5 * kStripeWidth, kStripeWidth))
    stripe.points.push_back(point(p));
  out.markers.push_back(stripe);

  Marker stem = marker(frame, stamp, "stem", kStemMarker, Marker::CYLINDER, {0.3f, 0.3f, 0.35f});
  stem.pose.position.z = 0.5 * (shape.stem_bottom + shape.stem_top);
  stem.scale.x = stem.scale.y = 2.0 * shape.stem_radius;
  stem.scale.z = shape.stem_top - shape.stem_bottom;
  out.markers.push_back(stem);
}

// Tip sphere and spin arrow in the top frame: fixed to the body, they cannot trail it. The spin arrow points
// along +f_hat for positive spin, -f_hat for negative (right-hand rule).
void add_tip_and_spin(const top_sim::Snapshot& s, const top_sim::Top& top, const std::string& frame,
                      const ros::Time& stamp, visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  const Eigen::Quaterniond to_body = s.orientation.normalized().conjugate();
  Marker tip = marker(frame, stamp, "tip", kTipMarker, Marker::SPHERE, {0.9f, 0.2f, 0.2f});
  tip.pose.position = point(to_body * (s.tip_center - s.com));
  tip.scale.x = tip.scale.y = tip.scale.z = 2.0 * top.tip_radius;
  if (top.com_offset < 0.0) tip.action = Marker::DELETE;  // a tippe top's sphere is its body
  out.markers.push_back(tip);

  Marker spin = marker(frame, stamp, "spin", kSpinMarker, Marker::ARROW, {0.1f, 0.5f, 1.0f});
  const double spin_len = arrow_length(s.spin, 100.0, 0.05) * (s.spin >= 0.0 ? 1.0 : -1.0);
  spin.points = {point(Eigen::Vector3d::Zero()), point(spin_len * (to_body * s.figure_axis))};
  spin.scale.x = 0.002; spin.scale.y = 0.004; spin.scale.z = 0.006;
  out.markers.push_back(spin);
}

// Velocity arrow and label in the contact frame (origin at the contact point, plane axes): they move with the
// top at the tf rate and keep their direction on the plane.
void add_contact_markers(const top_sim::Snapshot& s, const TopShape& shape, const MarkerStyle& style, Rgb colour,
                         const std::string& frame, const ros::Time& stamp, visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  Marker vel = marker(frame, stamp, "velocity", kVelocityMarker, Marker::ARROW, {0.1f, 0.8f, 0.2f});
  const double v = s.tip_velocity.norm();
  const Eigen::Vector3d dir = v > 0.0 ? Eigen::Vector3d(s.tip_velocity / v) : Eigen::Vector3d::Zero();
  vel.points = {point(Eigen::Vector3d::Zero()), point(arrow_length(v, 0.01, 0.05) * dir)};
  vel.scale.x = 0.002; vel.scale.y = 0.004; vel.scale.z = 0.006;
  out.markers.push_back(vel);

  Marker label = marker(frame, stamp, "label", kLabelMarker, Marker::TEXT_VIEW_FACING, colour);
  label.pose.position.z = (s.com - s.contact_point).z() + shape.stem_top + 0.02;
  label.scale.z = 0.008;  // text height [m]
  label.text = status_text(style.name, s);
  out.markers.push_back(label);
}

}  // namespace

bool parse_color_by(const std::string& text, ColorBy& out) {
  if (text == "regime") out = ColorBy::regime;
  else if (text == "mode") out = ColorBy::mode;
  else return false;
  return true;
}

Rgb body_colour(const top_sim::Snapshot& s, ColorBy by) {
  using top_sim::ContactMode;
  using top_sim::Regime;
  if (by == ColorBy::mode) {
    if (s.contact_mode == ContactMode::rolling) return {0.3f, 0.8f, 0.35f};
    if (s.contact_mode == ContactMode::flight) return {0.35f, 0.55f, 0.95f};
    return {0.7f, 0.7f, 0.75f};  // slipping: the paper's permanent slipping contact
  }
  switch (s.regime) {
    case Regime::sleeping: return {0.3f, 0.8f, 0.35f};
    case Regime::precessing: return {0.95f, 0.85f, 0.3f};
    case Regime::sliding: return {0.9f, 0.3f, 0.3f};
    case Regime::contact_fault: return {0.8f, 0.2f, 0.8f};
    case Regime::upright: return {0.3f, 0.75f, 0.9f};
    case Regime::inverting: return {0.95f, 0.45f, 0.6f};
    case Regime::inverted: return {0.45f, 0.35f, 0.95f};
    case Regime::tumbling: return {0.6f, 0.5f, 0.3f};
    case Regime::nutating: break;
  }
  return {1.0f, 0.6f, 0.2f};
}

std::string status_text(const std::string& name, const top_sim::Snapshot& s) {
  std::string text = name.empty() ? "" : name + ": ";
  if (s.regime == top_sim::Regime::contact_fault) return text + "fault: " + s.fault_message;
  char numbers[64];
  if (s.has_stationary_state)
    std::snprintf(numbers, sizeof numbers, ", phi %.3f / phi* %.3f", s.phi, s.phi_star);
  else
    std::snprintf(numbers, sizeof numbers, ", phi %.3f", s.phi);
  return text + top_sim::to_string(s.regime) + ", " + top_sim::to_string(s.contact_mode) + numbers;
}

void to_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                const MarkerStyle& style, visualization_msgs::MarkerArray& out) {
  out.markers.clear();
  const TopShape shape = top_shape(top);
  const Rgb colour = body_colour(s, style.color_by);
  add_plane(frames, stamp, style, out);
  add_body(shape, colour, frames.top, stamp, out);
  add_tip_and_spin(s, top, frames.top, stamp, out);
  add_contact_markers(s, shape, style, colour, frames.contact, stamp, out);
}

visualization_msgs::Marker trail_marker(const Trail& path, const ros::Time& stamp, const std::string& plane_frame) {
  using visualization_msgs::Marker;
  Marker trail = marker(plane_frame, stamp, "trail", kTrailMarker, Marker::LINE_STRIP,
                        {1.0f, 0.78f, 0.0f});
  trail.scale.x = 0.0015;  // line width [m]
  trail.points.reserve(path.points().size());
  for (const Trail::Point& p : path.points()) trail.points.push_back(point(p.position));
  if (trail.points.size() < 2) trail.action = Marker::DELETE;  // rviz rejects a strip of fewer than two points
  return trail;
}

}  // namespace top_sim_ros
