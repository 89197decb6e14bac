#include "markers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "control_layout.hpp"
#include "top_mesh.hpp"

namespace top_sim_ros {

namespace {

// Marker ids, one per kind and fixed: an update replaces the marker of the same (ns, id) in rviz. The trail's
// chunks have ids of their own in namespace "trail".
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
  kTrailHeadMarker,
  kTouchingMarker,
};

constexpr int kBodySegments = 32;        // facets round the body: smooth at rviz's usual distances
constexpr double kStripeWidth = 0.5;     // [rad] of the body's circumference painted, centred on body x
constexpr double kStripeRaise = 0.02;    // stripe height above the surface, relative to the body radius
constexpr float kBallAlpha = 0.6f;       // a ball-shaped top is see-through: its trail runs under it at first
constexpr double kLabelHeight = 0.008;   // [m] of one text line
constexpr Rgb kPlaneColour{0.25f, 0.30f, 0.45f};  // a dark blue: light label text reads on it and on rviz's grey
constexpr float kPlaneAlpha = 0.6f;
constexpr Rgb kRvizBackground{48.0f / 255.0f, 48.0f / 255.0f, 48.0f / 255.0f};  // rviz/top_sim.rviz
constexpr Rgb kTrailColour{1.0f, 0.78f, 0.0f};
constexpr Rgb kTouchingColour{1.0f, 1.0f, 1.0f};  // white: none of the regimes' or modes' colours

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
  Marker plane = marker(frames.grid, stamp, "plane", kPlaneMarker, Marker::CUBE, kPlaneColour);
  plane.pose.position.z = -0.001;
  plane.scale.x = plane.scale.y = 2.0 * half;
  plane.scale.z = 0.001;
  plane.color.a = kPlaneAlpha;
  out.markers.push_back(plane);

  Marker grid = marker(frames.grid, stamp, "grid", kGridMarker, Marker::LINE_LIST, {0.6f, 0.6f, 0.65f});
  grid.pose.position = plane.pose.position;
  grid.pose.position.z = -0.0004;
  grid.scale.x = 0.04 * style.grid_line_pitch;  // line width: a coarser grid of a fast top keeps thin lines
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

// The stem: a cylinder on the body, or for a ball-shaped top the cap of its sphere round the pole, painted (the
// physics has no stem: nothing sticks out of the sphere).
visualization_msgs::Marker stem_marker(const TopShape& shape, const std::string& frame, const ros::Time& stamp) {
  using visualization_msgs::Marker;
  const Rgb dark{0.3f, 0.3f, 0.35f};
  if (!shape.cap.empty()) {
    Marker cap = marker(frame, stamp, "stem", kStemMarker, Marker::TRIANGLE_LIST, dark);
    cap.scale.x = cap.scale.y = cap.scale.z = 1.0;
    for (const Eigen::Vector3d& p : revolve(shape.cap, kBodySegments, 0.0, 2.0 * M_PI)) cap.points.push_back(point(p));
    return cap;
  }
  Marker stem = marker(frame, stamp, "stem", kStemMarker, Marker::CYLINDER, dark);
  stem.pose.position.z = 0.5 * (shape.stem_bottom + shape.stem_top);
  stem.scale.x = stem.scale.y = 2.0 * shape.stem_radius;
  stem.scale.z = shape.stem_top - shape.stem_bottom;
  return stem;
}

// Body of revolution, a stripe fixed to the body (it turns with the spin phase that tf carries in the top frame)
// and the stem; all in the top frame.
void add_body(const TopShape& shape, Rgb colour, const std::string& frame, const ros::Time& stamp,
              visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  Marker body = marker(frame, stamp, "body", kBodyMarker, Marker::TRIANGLE_LIST, colour);
  body.scale.x = body.scale.y = body.scale.z = 1.0;  // TRIANGLE_LIST points are multiplied by the scale
  if (!shape.cap.empty()) body.color.a = kBallAlpha;
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
  out.markers.push_back(stem_marker(shape, frame, stamp));
}

// The tip sphere in the top frame (a ball-shaped top's sphere is its body).
void add_tip(const top_sim::Snapshot& s, const top_sim::Top& top, const std::string& frame, const ros::Time& stamp,
             visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  const Eigen::Quaterniond to_body = s.orientation.normalized().conjugate();
  Marker tip = marker(frame, stamp, "tip", kTipMarker, Marker::SPHERE, {0.9f, 0.2f, 0.2f});
  tip.pose.position = point(to_body * (s.tip_center - s.com));
  tip.scale.x = tip.scale.y = tip.scale.z = 2.0 * top.tip_radius;
  if (top.com_offset < 0.0) tip.action = Marker::DELETE;
  out.markers.push_back(tip);
}

// A body with contact shapes (top.shapes), all in the top frame: the body from its shapes in `colour`, the touching
// shape(s) in kTouchingColour (nothing in flight), a stripe on the widest shape; no tip sphere and no stem.
void add_shape_body(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes, Rgb colour,
                    const std::string& frame, const ros::Time& stamp, visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  // A lone rim's drawn thickness on the side away from the plane: f_hat up, towards +z of the top frame.
  const ShapeMesh mesh =
      shape_mesh(top, shapes, s.touching, s.figure_axis.z() >= 0.0, kBodySegments, kStripeWidth, kStripeRaise);
  auto triangles = [&](const char* ns, int id, Rgb c, const std::vector<Eigen::Vector3d>& points) {
    Marker m = marker(frame, stamp, ns, id, Marker::TRIANGLE_LIST, c);
    m.scale.x = m.scale.y = m.scale.z = 1.0;
    for (const Eigen::Vector3d& p : points) m.points.push_back(point(p));
    if (m.points.empty()) m.action = Marker::DELETE;  // in flight: no shape touches
    out.markers.push_back(m);
  };
  triangles("body", kBodyMarker, colour, mesh.body);
  triangles("touching", kTouchingMarker, kTouchingColour, mesh.touching);
  triangles("stripe", kStripeMarker, {1.0f, 0.5f, 0.0f}, mesh.stripe);
  for (const auto& [ns, id] : {std::make_pair("tip", kTipMarker), std::make_pair("stem", kStemMarker)}) {
    Marker gone = marker(frame, stamp, ns, id, Marker::SPHERE, colour);
    gone.action = Marker::DELETE;  // an ordinary top's parts: none on a body drawn from its shapes
    out.markers.push_back(gone);
  }
}

// The spin arrow in the top frame, fixed to the body: along +f_hat for positive spin, -f_hat for negative.
visualization_msgs::Marker spin_marker(const top_sim::Snapshot& s, const std::string& frame, const ros::Time& stamp) {
  using visualization_msgs::Marker;
  const Eigen::Quaterniond to_body = s.orientation.normalized().conjugate();
  Marker spin = marker(frame, stamp, "spin", kSpinMarker, Marker::ARROW, {0.1f, 0.5f, 1.0f});
  const double spin_len = arrow_length(s.spin, 100.0, 0.05) * (s.spin >= 0.0 ? 1.0 : -1.0);
  spin.points = {point(Eigen::Vector3d::Zero()), point(spin_len * (to_body * s.figure_axis))};
  spin.scale.x = 0.002; spin.scale.y = 0.004; spin.scale.z = 0.006;
  return spin;
}

// Velocity arrow and label in the contact frame (origin at the contact point, plane axes): they move with the
// top at the tf rate and keep their direction on the plane. The label sits above the top and above the controls.
void add_contact_markers(const top_sim::Snapshot& s, double body_top, const top_sim::ShapeSet& shapes,
                         const MarkerStyle& style, Rgb colour, const std::string& frame, const ros::Time& stamp,
                         visualization_msgs::MarkerArray& out) {
  using visualization_msgs::Marker;
  Marker vel = marker(frame, stamp, "velocity", kVelocityMarker, Marker::ARROW, {0.1f, 0.8f, 0.2f});
  const double v = s.tip_velocity.norm();
  const Eigen::Vector3d dir = v > 0.0 ? Eigen::Vector3d(s.tip_velocity / v) : Eigen::Vector3d::Zero();
  vel.points = {point(Eigen::Vector3d::Zero()), point(arrow_length(v, 0.01, 0.05) * dir)};
  vel.scale.x = 0.002; vel.scale.y = 0.004; vel.scale.z = 0.006;
  out.markers.push_back(vel);

  Marker label = marker(frame, stamp, "label", kLabelMarker, Marker::TEXT_VIEW_FACING, readable(colour));
  const double above_top = (s.com - s.contact_point).z() + body_top + 0.02;
  label.text = status_text(style.name, s, "\n", &shapes);
  const double lines = 1.0 + static_cast<double>(std::count(label.text.begin(), label.text.end(), '\n'));
  // Centred text: half its height above the controls keeps its lowest line clear of them.
  label.pose.position.z = std::max(above_top, control_layout::kTop + (0.5 * lines + 0.5) * kLabelHeight);
  label.scale.z = kLabelHeight;
  out.markers.push_back(label);
}

// sRGB channel -> linear light (WCAG 2's relative luminance).
double linear(float c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double luminance(Rgb c) { return 0.2126 * linear(c.r) + 0.7152 * linear(c.g) + 0.0722 * linear(c.b); }

// "1.2 mm/s", "3.4 cm/s", "50.1 m/s": three digits whatever the speed.
std::string speed_text(double v) {
  char text[32];
  if (v >= 1.0) std::snprintf(text, sizeof text, "%.1f m/s", v);
  else if (v >= 0.01) std::snprintf(text, sizeof text, "%.1f cm/s", 100.0 * v);
  else std::snprintf(text, sizeof text, "%.2f mm/s", 1000.0 * v);
  return text;
}

// The patch and its drilling torque, only on a finite contact: a point contact's label stays as it was.
std::string finite_contact_text(const top_sim::Snapshot& s, const std::string& line_break) {
  if (!(s.patch_radius > 0.0) && s.drilling_torque == 0.0) return "";
  char text[64];
  std::snprintf(text, sizeof text, "a %.3g mm, M_n %.3g N m", 1000.0 * s.patch_radius, s.drilling_torque);
  return line_break + text;
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
    case Regime::rolling: return {0.25f, 0.75f, 0.75f};
    case Regime::on_crown: return {0.55f, 0.45f, 0.9f};
    case Regime::on_stem: return {0.75f, 0.4f, 0.85f};
    // The story has ended: greys, a still object (each its own, for a reader that tells them by colour).
    case Regime::at_rest: return {0.6f, 0.62f, 0.66f};
    case Regime::lying_flat: return {0.5f, 0.54f, 0.6f};
    case Regime::fallen: return {0.7f, 0.66f, 0.6f};
    case Regime::nutating: break;
  }
  return {1.0f, 0.6f, 0.2f};
}

double contrast_ratio(Rgb a, Rgb b) {
  const double la = luminance(a), lb = luminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

Rgb rviz_background() { return kRvizBackground; }

Rgb plane_over_background() {
  auto over = [](float plane, float back) { return kPlaneAlpha * plane + (1.0f - kPlaneAlpha) * back; };
  return {over(kPlaneColour.r, kRvizBackground.r), over(kPlaneColour.g, kRvizBackground.g),
          over(kPlaneColour.b, kRvizBackground.b)};
}

// Both backgrounds are dark, so text reads when it is light enough against the lighter one; white reaches 7.7:1.
Rgb readable(Rgb c, double ratio) {
  const Rgb back = luminance(plane_over_background()) > luminance(kRvizBackground) ? plane_over_background()
                                                                                   : kRvizBackground;
  for (int step = 0; step <= 100; ++step) {
    const float w = 0.01f * step;
    const Rgb mixed{c.r + w * (1.0f - c.r), c.g + w * (1.0f - c.g), c.b + w * (1.0f - c.b)};
    if (contrast_ratio(mixed, back) >= ratio) return mixed;
  }
  return {1.0f, 1.0f, 1.0f};
}

double speed_on_plane(const top_sim::Snapshot& s) { return s.com_velocity.head<2>().norm(); }

double grid_pitch_for(double speed, double base, double current) {
  constexpr double kFrame = 1.0 / 30.0;  // [s] between frames rviz draws
  const double needed = 3.0 * speed * kFrame;
  double pitch = base;
  while (pitch < needed && pitch < 1e6 * base) pitch *= 10.0;
  // Keep a coarser pitch until the finer one would be twice as much as needed: a speed near a step does not flip it.
  if (pitch < current && needed > 0.5 * pitch) return current;
  return pitch;
}

namespace {

// The regime word, or with the body's shapes what it touches with: "rolling on tip and crown", "on stem".
std::string regime_text(const top_sim::Snapshot& s, const top_sim::ShapeSet* shapes) {
  using top_sim::Regime;
  const bool named = shapes != nullptr && shapes->active && s.touching != 0;
  if (named && s.regime == Regime::rolling) return "rolling on " + top_sim::touching_names(*shapes, s.touching);
  if (named && (s.regime == Regime::on_crown || s.regime == Regime::on_stem))
    return "on " + top_sim::touching_names(*shapes, s.touching);
  return top_sim::to_string(s.regime);
}

}  // namespace

std::string status_text(const std::string& name, const top_sim::Snapshot& s, const std::string& line_break,
                        const top_sim::ShapeSet* shapes) {
  std::string text = name.empty() ? "" : name + ": ";
  if (s.regime == top_sim::Regime::contact_fault) return text + "fault: " + s.fault_message;
  char numbers[64];
  if (s.end_state != top_sim::EndState::none) {  // stopped there: its end and when, no motion that has stopped
    std::snprintf(numbers, sizeof numbers, "end: %s at t = %.2f s", top_sim::to_string(s.end_state), s.t);
    return text + numbers;
  }
  if (s.has_stationary_state)
    std::snprintf(numbers, sizeof numbers, "phi %.3f / phi* %.3f", s.phi, s.phi_star);
  else
    std::snprintf(numbers, sizeof numbers, "phi %.3f", s.phi);
  text += regime_text(s, shapes) + ", " + top_sim::to_string(s.contact_mode) + line_break;
  return text + numbers + ", v " + speed_text(speed_on_plane(s)) + finite_contact_text(s, line_break);
}

void fixed_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes,
                   const ros::Time& stamp, const Frames& frames, const MarkerStyle& style,
                   visualization_msgs::MarkerArray& out) {
  add_plane(frames, stamp, style, out);
  if (shapes.active) {
    add_shape_body(s, top, shapes, body_colour(s, style.color_by), frames.top, stamp, out);
    return;
  }
  add_body(top_shape(top), body_colour(s, style.color_by), frames.top, stamp, out);
  add_tip(s, top, frames.top, stamp, out);
}

void moving_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes,
                    const ros::Time& stamp, const Frames& frames, const MarkerStyle& style,
                    visualization_msgs::MarkerArray& out) {
  out.markers.push_back(spin_marker(s, frames.top, stamp));
  const double body_top = shapes.active ? shape_reach(top, shapes) : top_shape(top).stem_top;
  add_contact_markers(s, body_top, shapes, style, body_colour(s, style.color_by), frames.contact, stamp, out);
}

void to_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes,
                const ros::Time& stamp, const Frames& frames, const MarkerStyle& style,
                visualization_msgs::MarkerArray& out) {
  out.markers.clear();
  fixed_markers(s, top, shapes, stamp, frames, style, out);
  moving_markers(s, top, shapes, stamp, frames, style, out);
}

void fixed_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                   const MarkerStyle& style, visualization_msgs::MarkerArray& out) {
  fixed_markers(s, top, top_sim::ShapeSet(), stamp, frames, style, out);
}

void moving_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                    const MarkerStyle& style, visualization_msgs::MarkerArray& out) {
  moving_markers(s, top, top_sim::ShapeSet(), stamp, frames, style, out);
}

void to_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                const MarkerStyle& style, visualization_msgs::MarkerArray& out) {
  to_markers(s, top, top_sim::ShapeSet(), stamp, frames, style, out);
}

visualization_msgs::Marker trail_chunk_marker(const Trail::Chunk& chunk, const ros::Time& stamp,
                                              const std::string& plane_frame) {
  using visualization_msgs::Marker;
  Marker m = marker(plane_frame, stamp, "trail", static_cast<int>(chunk.id), Marker::LINE_STRIP, kTrailColour);
  m.frame_locked = false;  // the plane frame does not move
  m.scale.x = 0.0015;      // line width [m]
  m.points.reserve(chunk.points.size());
  for (const Trail::Point& p : chunk.points) m.points.push_back(point(p.position));
  if (m.points.size() < 2) m.action = Marker::DELETE;  // rviz rejects a strip of fewer than two points
  return m;
}

visualization_msgs::Marker trail_head_marker(const Trail& trail, const Eigen::Vector3d& contact,
                                             const ros::Time& stamp, const Frames& frames, bool attached) {
  using visualization_msgs::Marker;
  // Frame-locked in both frames: rviz 1.14 keeps a marker that came frame-locked in its frame-locked set when an
  // update of the same (ns, id, type) is not, and then aborts (ROS_ASSERT in MarkerBase::updateFrameLocked: SIGTRAP,
  // issue 46); the plane frame moves only with alpha, so re-reading its tf each frame costs nothing wrong.
  Marker m = marker(attached ? frames.contact : frames.plane, stamp, "trail_head", kTrailHeadMarker,
                    Marker::LINE_STRIP, kTrailColour);
  m.scale.x = 0.0015;
  const Eigen::Vector3d origin = attached ? contact : Eigen::Vector3d::Zero();
  if (!trail.empty())
    for (const Trail::Point& p : trail.chunks().back().points) m.points.push_back(point(p.position - origin));
  if (m.points.size() >= 2) m.points.push_back(point(contact - origin));  // up to the contact point
  if (m.points.size() < 2) m.action = Marker::DELETE;
  return m;
}

}  // namespace top_sim_ros
