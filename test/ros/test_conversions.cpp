// Unit tests of the ROS adapter's pure maps (no master needed): TopCommand -> Command,
// Snapshot -> tf / TopState -> Snapshot, the top's mesh.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "control_layout.hpp"
#include "conversions.hpp"
#include "markers.hpp"
#include "top_mesh.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/trajectory.hpp"

using top_sim_ros::command_from_message;

TEST(TopCommand, OnlySetFieldsAreCarried) {
  top_sim::TopCommand m;
  m.set_inclination = true;
  m.inclination = 0.2;
  m.spin = 99.0;  // not set: ignored
  std::string error;
  const top_sim::Command c = command_from_message(m, error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(c.inclination);
  EXPECT_EQ(*c.inclination, 0.2);
  EXPECT_FALSE(c.spin);
  EXPECT_FALSE(c.friction);
}

TEST(TopCommand, FrictionLawByName) {
  top_sim::TopCommand m;
  m.set_friction = true;
  m.friction_law = "table";
  m.table_s = {0.0, 0.5, 1.0};
  m.table_mu = {0.0, 0.3, 0.2};
  std::string error;
  top_sim::Command c = command_from_message(m, error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(c.friction);
  EXPECT_EQ(c.friction->kind, top_sim::FrictionLawKind::table);
  ASSERT_TRUE(c.friction->points);
  ASSERT_EQ(c.friction->points->size(), 3u);
  EXPECT_EQ((*c.friction->points)[1].second, 0.3);

  m.table_mu.pop_back();
  command_from_message(m, error);
  EXPECT_NE(error.find("table_mu"), std::string::npos) << error;

  m.friction_law = "viscous";
  command_from_message(m, error);
  EXPECT_NE(error.find("friction_law = 'viscous'"), std::string::npos) << error;
}

// Every scalar parameter of the core's table reaches the law it belongs to (the message's fields carry the
// parameters' names); the other laws' parameters keep their values in force.
TEST(TopCommand, EveryFrictionParameterIsCarried) {
  for (const char* law : {"paper", "linearized", "coulomb"}) {
    top_sim::TopCommand m;
    m.set_friction = true;
    m.friction_law = law;
    double value = 0.0;
#define TOP_SIM_SET_FIELD(kind, name, range) m.name = (value += 0.125);
    TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_SET_FIELD)
#undef TOP_SIM_SET_FIELD
    std::string error;
    const top_sim::FrictionLaw in_force;
    const top_sim::Command c = command_from_message(m, error);
    EXPECT_EQ(error, "");
    ASSERT_TRUE(c.friction);
    value = 0.0;
    for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters) {
      value += 0.125;
      const double expected = std::string(top_sim::to_string(p.law)) == law ? value : in_force.*p.member;
      EXPECT_EQ(top_sim::changed_law(in_force, *c.friction).*p.member, expected) << law << ": " << p.name;
    }
  }
}

// One rule with Python's apply and dynamic_reconfigure: law parameters a TopCommand does not give keep their values
// in the law in force (the issue: {friction_law: paper, mu_c: 0.3} turned s_c into 0 and was refused).
TEST(TopCommand, LawParametersNotGivenKeepTheLawInForce) {
  top_sim::FrictionLaw in_force;
  in_force.kind = top_sim::FrictionLawKind::paper;
  in_force.mu_c = 0.25;
  in_force.s_c = 0.45;
  in_force.mu = 0.7;
  top_sim::TopCommand m;
  m.set_friction = true;
  m.friction_law = "paper";
  m.mu_c = 0.3;
  std::string error;
  top_sim::Command c = command_from_message(m, error);
  ASSERT_EQ(error, "");
  ASSERT_TRUE(c.friction);
  const top_sim::FrictionLaw paper = top_sim::changed_law(in_force, *c.friction);
  EXPECT_EQ(paper.mu_c, 0.3);
  EXPECT_EQ(paper.s_c, 0.45) << "s_c not given: the law in force's";
  EXPECT_EQ(top_sim::validate(paper), "");
  // A true zero is given by name: a frictionless Coulomb law.
  top_sim::TopCommand z;
  z.set_friction = true;
  z.friction_law = "coulomb";
  z.friction_given = {"mu"};
  c = command_from_message(z, error);
  ASSERT_EQ(error, "");
  EXPECT_EQ(c.friction->kind, top_sim::FrictionLawKind::coulomb);
  EXPECT_EQ(top_sim::changed_law(in_force, *c.friction).mu, 0.0);
  z.friction_given.clear();  // nothing given: Coulomb with the mu in force
  c = command_from_message(z, error);
  EXPECT_EQ(top_sim::changed_law(in_force, *c.friction).mu, 0.7);
  z.friction_given = {"mu_c"};
  command_from_message(z, error);
  EXPECT_EQ(error, "friction_given: 'mu_c': the coulomb law reads mu");
}

TEST(TopCommand, EmptyCommandIsReported) {
  std::string error;
  command_from_message(top_sim::TopCommand(), error);
  EXPECT_NE(error.find("no field is set"), std::string::npos) << error;
  top_sim::TopCommand control;  // reset or pause alone is a command (the node's, not the core's: NodeTop::command)
  control.reset = true;
  EXPECT_TRUE(command_from_message(control, error).empty());
  EXPECT_EQ(error, "");
  control.reset = false;
  control.set_paused = true;
  EXPECT_TRUE(command_from_message(control, error).empty());
  EXPECT_EQ(error, "");
}

TEST(Transforms, PlaneIsTiltedByAlphaAboutXAndUphillRises) {
  top_sim::TopPose s;
  s.alpha = 0.3;
  s.com = Eigen::Vector3d(0.1, 0.2, 0.01);
  geometry_msgs::TransformStamped wp, pt;
  top_sim_ros::to_transforms(s, ros::Time(10.0), top_sim_ros::Frames(), wp, pt);
  EXPECT_EQ(wp.header.frame_id, "world");
  EXPECT_EQ(wp.child_frame_id, "plane");
  EXPECT_EQ(pt.header.frame_id, "plane");
  EXPECT_EQ(pt.child_frame_id, "top");
  const auto& q = wp.transform.rotation;
  const Eigen::Quaterniond r(q.w, q.x, q.y, q.z);
  // Plane y (uphill) seen from world: (0, cos alpha, sin alpha).
  const Eigen::Vector3d up = r * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(up.y(), std::cos(0.3), 1e-15);
  EXPECT_NEAR(up.z(), std::sin(0.3), 1e-15);
  EXPECT_EQ(pt.transform.translation.y, 0.2);
}

TEST(Snapshot, NonFiniteValuesAreDetected) {
  top_sim::Snapshot s;
  EXPECT_TRUE(top_sim::all_finite(s));
  s.friction_force.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(top_sim::all_finite(s));
  s.friction_force.y() = 0.0;
  s.mu = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(top_sim::all_finite(s));
}

TEST(TopStateMsg, RegimeConstantsMatchTheCore) {
  EXPECT_EQ(top_sim::code(top_sim::Regime::sleeping), top_sim::TopState::SLEEPING);
  EXPECT_EQ(top_sim::code(top_sim::Regime::contact_fault), top_sim::TopState::CONTACT_FAULT);
  top_sim::Snapshot s;
  s.t = 2.5;
  s.regime = top_sim::Regime::sliding;
  top_sim::TopState m;
  top_sim_ros::to_msg(s, ros::Time(5.0), "plane", m);
  EXPECT_EQ(m.regime, top_sim::TopState::SLIDING);
  EXPECT_EQ(m.regime_name, "sliding");
  EXPECT_EQ(m.sim_time, 2.5);
}

TEST(TopStateMsg, ContactModeAndGapAreMapped) {
  EXPECT_EQ(top_sim::code(top_sim::ContactMode::slipping), top_sim::TopState::SLIPPING);
  EXPECT_EQ(top_sim::code(top_sim::ContactMode::rolling), top_sim::TopState::ROLLING);
  EXPECT_EQ(top_sim::code(top_sim::ContactMode::flight), top_sim::TopState::FLIGHT);
  const struct {
    top_sim::ContactMode mode;
    uint8_t code;
    const char* name;
    double gap;
  } cases[] = {{top_sim::ContactMode::slipping, top_sim::TopState::SLIPPING, "slipping", 0.0},
               {top_sim::ContactMode::rolling, top_sim::TopState::ROLLING, "rolling", 0.0},
               {top_sim::ContactMode::flight, top_sim::TopState::FLIGHT, "flight", 2.5e-4}};
  for (const auto& k : cases) {
    top_sim::Snapshot s;
    s.contact_mode = k.mode;
    s.gap = k.gap;
    top_sim::TopState m;
    top_sim_ros::to_msg(s, ros::Time(1.0), "plane", m);
    EXPECT_EQ(m.contact_mode, k.code) << k.name;
    EXPECT_EQ(m.contact_mode_name, k.name);
    EXPECT_EQ(m.gap, k.gap) << k.name;
  }
  top_sim::Snapshot s;
  s.gap = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(top_sim::all_finite(s)) << "a NaN gap must not be published";
}

bool same(const std_msgs::ColorRGBA& a, const std_msgs::ColorRGBA& b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

const visualization_msgs::Marker& find_marker_or_fail(const visualization_msgs::MarkerArray& a, const std::string& ns) {
  for (const auto& m : a.markers)
    if (m.ns == ns) return m;
  ADD_FAILURE() << "no marker " << ns;
  static const visualization_msgs::Marker none;
  return none;
}

top_sim::Top small_top() {
  top_sim::Top top;
  top.mass = 0.025;
  top.inertia_axial = 5e-6;
  top.tip_radius = 1.5e-3;
  top.com_offset = 0.01;
  return top;
}

// Colour by mode: the three contact modes differ; colour by regime: the five regimes differ.
TEST(Markers, BodyColourShowsTheModeOrTheRegime) {
  using top_sim_ros::ColorBy;
  top_sim::Snapshot s;
  std::vector<std_msgs::ColorRGBA> seen;
  auto body = [&](ColorBy by) {
    top_sim_ros::MarkerStyle style;
    style.color_by = by;
    visualization_msgs::MarkerArray a;
    top_sim_ros::to_markers(s, small_top(), ros::Time(1.0), top_sim_ros::Frames(), style, a);
    return find_marker_or_fail(a, "body").color;
  };
  for (auto mode : {top_sim::ContactMode::slipping, top_sim::ContactMode::rolling, top_sim::ContactMode::flight}) {
    s.contact_mode = mode;
    seen.push_back(body(ColorBy::mode));
  }
  for (std::size_t i = 0; i < seen.size(); ++i)
    for (std::size_t j = i + 1; j < seen.size(); ++j) EXPECT_FALSE(same(seen[i], seen[j])) << "modes " << i << ", " << j;
  seen.clear();
  for (int r = 0; r < top_sim::kRegimeCount; ++r) {
    s.regime = static_cast<top_sim::Regime>(r);
    seen.push_back(body(ColorBy::regime));
  }
  for (std::size_t i = 0; i < seen.size(); ++i)
    for (std::size_t j = i + 1; j < seen.size(); ++j)
      EXPECT_FALSE(same(seen[i], seen[j])) << top_sim::to_string(static_cast<top_sim::Regime>(i)) << " and "
                                           << top_sim::to_string(static_cast<top_sim::Regime>(j));
  top_sim_ros::ColorBy by;
  EXPECT_TRUE(top_sim_ros::parse_color_by("mode", by));
  EXPECT_EQ(by, ColorBy::mode);
  EXPECT_FALSE(top_sim_ros::parse_color_by("Regime", by));
}

// The label names the top, its regime and contact mode on one line, phi, phi* (when there is one) and the contact
// point's speed on the plane on the next (in units that keep three digits); a fault replaces them.
TEST(Markers, LabelShowsRegimeModePhiAndSpeed) {
  top_sim::Snapshot s;
  s.regime = top_sim::Regime::sleeping;
  s.contact_mode = top_sim::ContactMode::slipping;
  s.phi = 0.2701;
  s.has_stationary_state = true;
  s.phi_star = 0.2699;
  s.com_velocity = Eigen::Vector3d(3e-4, -4e-4, 7.0);  // 0.5 mm/s along the plane; the normal part is not the speed
  EXPECT_EQ(top_sim_ros::status_text("top", s), "top: sleeping, slipping, phi 0.270 / phi* 0.270, v 0.50 mm/s");
  EXPECT_EQ(top_sim_ros::status_text("top", s, "\n"), "top: sleeping, slipping\nphi 0.270 / phi* 0.270, v 0.50 mm/s");
  s.has_stationary_state = false;
  s.regime = top_sim::Regime::sliding;
  s.com_velocity = Eigen::Vector3d(30.0, -40.0, 0.0);
  EXPECT_EQ(top_sim_ros::status_text("b", s), "b: sliding, slipping, phi 0.270, v 50.0 m/s");
  s.com_velocity = Eigen::Vector3d(0.0, 0.034, 0.0);
  EXPECT_EQ(top_sim_ros::status_text("b", s), "b: sliding, slipping, phi 0.270, v 3.4 cm/s");
  s.patch_radius = 2.0e-4;  // a finite contact adds its patch and drilling torque; a point contact's text is unchanged
  s.drilling_torque = -1.25e-5;
  EXPECT_EQ(top_sim_ros::status_text("b", s, "\n"),
            "b: sliding, slipping\nphi 0.270, v 3.4 cm/s\na 0.2 mm, M_n -1.25e-05 N m");
  s.patch_radius = 0.0;
  s.drilling_torque = 0.0;
  s.regime = top_sim::Regime::contact_fault;
  s.fault_message = "penetration 2 mm";
  EXPECT_EQ(top_sim_ros::status_text("b", s), "b: fault: penetration 2 mm");
  top_sim_ros::MarkerStyle style;
  style.name = "b";
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(s, small_top(), ros::Time(1.0), top_sim_ros::Frames(), style, a);
  EXPECT_EQ(find_marker_or_fail(a, "label").text, "b: fault: penetration 2 mm");
  s.regime = top_sim::Regime::sliding;
  top_sim_ros::to_markers(s, small_top(), ros::Time(1.0), top_sim_ros::Frames(), style, a);
  EXPECT_EQ(find_marker_or_fail(a, "label").text, "b: sliding, slipping\nphi 0.270, v 3.4 cm/s") << "two lines";
  EXPECT_EQ(find_marker_or_fail(a, "label").type, visualization_msgs::Marker::TEXT_VIEW_FACING);
}

// A body of shapes says what it touches with, by the shapes' names ("shape i" unnamed); a top at its end shows only
// that end and its time, no motion that has stopped (issue 46).
TEST(Markers, LabelNamesTheTouchingShapesAndAnEnd) {
  top_sim::ShapeSet shapes;
  shapes.shape[0] = {top_sim::ShapeKind::sphere, -0.010, 1.5e-3, {'t', 'i', 'p'}};
  shapes.shape[1] = {top_sim::ShapeKind::rim, 0.004, 0.02, {'c', 'r', 'o', 'w', 'n'}};
  shapes.shape[2] = {top_sim::ShapeKind::sphere, 0.02, 1e-3};
  shapes.count = 3;
  shapes.active = top_sim::shapes_active(shapes);
  top_sim::Snapshot s;
  s.contact_mode = top_sim::ContactMode::slipping;
  s.phi = 0.5;
  s.regime = top_sim::Regime::rolling;
  s.touching = 0b011;
  EXPECT_EQ(top_sim_ros::status_text("top", s, ", ", &shapes), "top: rolling on tip and crown, slipping, phi 0.500, v 0.00 mm/s");
  EXPECT_EQ(top_sim_ros::status_text("top", s), "top: rolling, slipping, phi 0.500, v 0.00 mm/s") << "no shapes: the word";
  s.touching = 0b111;
  EXPECT_EQ(top_sim_ros::status_text("", s, ", ", &shapes).substr(0, 34), "rolling on tip, crown and shape 2,");
  s.regime = top_sim::Regime::on_crown;
  s.touching = 0b010;
  EXPECT_EQ(top_sim_ros::status_text("", s, "\n", &shapes), "on crown, slipping\nphi 0.500, v 0.00 mm/s");
  s.regime = top_sim::Regime::at_rest;
  s.end_state = top_sim::EndState::at_rest;
  s.t = 69.7315;
  s.touching = 0b011;
  EXPECT_EQ(top_sim_ros::status_text("top", s, "\n", &shapes), "top: end: at_rest at t = 69.73 s");
}

// Label text reads on what is behind it: every regime's and mode's label colour has a WCAG contrast ratio of at
// least 4.5:1 against rviz's background (the one rviz/top_sim.rviz sets) and against the plane square over it,
// and keeps the hue of its body colour (mixed with white only). The ratio itself: 21 for black on white.
TEST(Markers, LabelColoursHaveContrastOnTheBackground) {
  using top_sim_ros::Rgb;
  EXPECT_NEAR(top_sim_ros::contrast_ratio({0, 0, 0}, {1, 1, 1}), 21.0, 1e-9);
  EXPECT_NEAR(top_sim_ros::contrast_ratio({0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}), 1.0, 1e-12);
  std::ifstream rviz(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/../rviz/top_sim.rviz");
  ASSERT_TRUE(rviz.good());
  const YAML::Node config = YAML::Load(rviz);
  const std::string back = config["Visualization Manager"]["Global Options"]["Background Color"].as<std::string>();
  const Rgb bg = top_sim_ros::rviz_background();
  char expected[32];
  std::snprintf(expected, sizeof expected, "%.0f; %.0f; %.0f", 255.0 * bg.r, 255.0 * bg.g, 255.0 * bg.b);
  EXPECT_EQ(back, expected) << "markers.cpp's background is not rviz/top_sim.rviz's";
  top_sim::Snapshot s;
  std::vector<top_sim_ros::Rgb> colours;
  for (int r = 0; r < top_sim::kRegimeCount; ++r) {
    s.regime = static_cast<top_sim::Regime>(r);
    colours.push_back(top_sim_ros::body_colour(s, top_sim_ros::ColorBy::regime));
  }
  for (auto mode : {top_sim::ContactMode::slipping, top_sim::ContactMode::rolling, top_sim::ContactMode::flight}) {
    s.contact_mode = mode;
    colours.push_back(top_sim_ros::body_colour(s, top_sim_ros::ColorBy::mode));
  }
  for (const Rgb& c : colours) {
    const Rgb text = top_sim_ros::readable(c);
    EXPECT_GE(top_sim_ros::contrast_ratio(text, bg), 4.5) << c.r << " " << c.g << " " << c.b;
    EXPECT_GE(top_sim_ros::contrast_ratio(text, top_sim_ros::plane_over_background()), 4.5);
    // mixed with white: each channel moved the same fraction w towards 1
    const double w = c.r < 1.0f ? (text.r - c.r) / (1.0 - c.r) : (text.g - c.g) / (1.0 - c.g);
    EXPECT_GE(w, 0.0);
    if (c.g < 1.0f) {
      EXPECT_NEAR(text.g, c.g + w * (1.0 - c.g), 1e-5);
    }
    if (c.b < 1.0f) {
      EXPECT_NEAR(text.b, c.b + w * (1.0 - c.b), 1e-5);
    }
  }
}

// The grid's pitch grows by tens with the contact point's speed so that its lines move at most a third of a pitch
// per frame at 30 Hz (no aliasing), and comes back only when the finer pitch is twice what is needed.
TEST(Markers, GridPitchGrowsWithSpeedWithoutFlicker) {
  const double base = 0.05;
  EXPECT_EQ(top_sim_ros::grid_pitch_for(0.0, base, base), base);
  EXPECT_EQ(top_sim_ros::grid_pitch_for(0.4, base, base), base);  // 0.04 m per frame... 3 x 0.4 / 30 = 0.04
  for (const double v : {0.5, 3.0, 50.0, 700.0}) {
    const double pitch = top_sim_ros::grid_pitch_for(v, base, base);
    EXPECT_GE(pitch, 3.0 * v / 30.0) << v;
    EXPECT_LT(pitch / 10.0, 3.0 * v / 30.0) << v << ": not the finest that is enough";
    EXPECT_NEAR(std::log10(pitch / base), std::round(std::log10(pitch / base)), 1e-9);
  }
  EXPECT_EQ(top_sim_ros::grid_pitch_for(45.0, base, 5.0), 5.0);
  EXPECT_EQ(top_sim_ros::grid_pitch_for(4.0, base, 5.0), 5.0) << "0.5 m would be only 1.25 x what 4 m/s needs";
  EXPECT_EQ(top_sim_ros::grid_pitch_for(2.0, base, 5.0), 0.5);
}

// Nothing drawn on the top is placed in the plane frame from a snapshot (it would trail the top by speed /
// marker_rate): tip and spin arrow are in the top frame, the velocity arrow and label in the contact frame; all
// frame-locked. The tip sphere sits f below the centre of mass on the figure axis.
TEST(Markers, TopMarkersAreAttachedToFramesThatTfMoves) {
  top_sim::Simulator sim(top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/supercritical.yaml"));
  ASSERT_TRUE(sim.advance_to(1.0));
  const top_sim::Snapshot s = sim.snapshot();
  const top_sim::Top& top = sim.model().top;
  top_sim_ros::Frames frames;
  frames.top = "b/top";
  frames.contact = "b/contact";
  frames.plane = "b/plane";
  frames.grid = "b/grid";
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(s, top, ros::Time(1.0), frames, top_sim_ros::MarkerStyle(), a);
  for (const auto& m : a.markers) {
    EXPECT_TRUE(m.frame_locked) << m.ns;
    if (m.ns == "plane" || m.ns == "grid") EXPECT_EQ(m.header.frame_id, "b/grid") << m.ns;
    else if (m.ns == "velocity" || m.ns == "label") EXPECT_EQ(m.header.frame_id, "b/contact") << m.ns;
    else EXPECT_EQ(m.header.frame_id, "b/top") << m.ns;
  }
  const auto& tip = find_marker_or_fail(a, "tip").pose.position;
  EXPECT_NEAR(tip.x, 0.0, 1e-12);
  EXPECT_NEAR(tip.y, 0.0, 1e-12);
  EXPECT_NEAR(tip.z, -top.com_offset, 1e-12);
  const auto& spin = find_marker_or_fail(a, "spin").points;
  ASSERT_EQ(spin.size(), 2u);
  EXPECT_NEAR(std::hypot(spin[1].x, spin[1].y), 0.0, 1e-12) << "the spin arrow lies on the figure axis";
  const auto& vel = find_marker_or_fail(a, "velocity").points;
  ASSERT_EQ(vel.size(), 2u);
  EXPECT_EQ(vel[0].x, 0.0);
  const Eigen::Vector3d arrow(vel[1].x, vel[1].y, vel[1].z);
  EXPECT_GT(arrow.normalized().dot(s.tip_velocity.normalized()), 1.0 - 1e-12) << "keeps the velocity's direction";
}

// The grid stays on the plane's lattice (its frame at multiples of the pitch) and under the contact point, at any
// distance from the origin; its lines are drawn about the grid frame's origin.
TEST(Markers, GridIsSnappedToThePitchAroundTheContactPoint) {
  top_sim::Snapshot s;
  s.contact_point = Eigen::Vector3d(1234.5678, -98.7654, 0.0);
  top_sim::TopPose pose;  // what tf reads
  pose.contact_point = s.contact_point;
  geometry_msgs::TransformStamped g;
  top_sim_ros::to_grid_transform(pose, 0.05, ros::Time(1.0), top_sim_ros::Frames(), g);
  EXPECT_EQ(g.header.frame_id, "plane");
  EXPECT_EQ(g.child_frame_id, "grid");
  for (const double c : {g.transform.translation.x, g.transform.translation.y})
    EXPECT_NEAR(c / 0.05, std::round(c / 0.05), 1e-6) << "centre on the lattice";
  EXPECT_LE(std::abs(g.transform.translation.x - s.contact_point.x()), 0.025 + 1e-9);
  EXPECT_LE(std::abs(g.transform.translation.y - s.contact_point.y()), 0.025 + 1e-9);
  EXPECT_EQ(g.transform.translation.z, 0.0);
  top_sim_ros::MarkerStyle style;
  style.grid_pitch = 0.05;
  style.grid_cells = 10;
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(s, small_top(), ros::Time(1.0), top_sim_ros::Frames(), style, a);
  const auto& grid = find_marker_or_fail(a, "grid");
  EXPECT_EQ(grid.header.frame_id, "grid");
  EXPECT_EQ(grid.type, visualization_msgs::Marker::LINE_LIST);
  EXPECT_EQ(grid.points.size(), 4u * 11u);
  EXPECT_NEAR(grid.points.front().x, -0.25, 1e-12);
  EXPECT_NEAR(grid.pose.position.x, 0.0, 1e-12);
}

// The three tops of config/tops and the homogeneous ball (f = 0, body inside the tip sphere) of config/scenes.
std::vector<top_sim::Top> drawn_tops() {
  std::vector<top_sim::Top> tops;
  for (const char* name : {"aluminium", "steel", "wood"}) {
    const YAML::Node y = YAML::Load(std::string("top: ") + name);
    tops.push_back(top_sim::parse_scene(y, "test", TOP_SIM_TEST_CONFIG_DIR).model.top);
  }
  top_sim::Top ball;
  ball.mass = 0.1; ball.tip_radius = 0.01; ball.com_offset = 0.0;
  ball.inertia_axial = ball.inertia_transverse = 4.0e-6;
  tops.push_back(ball);
  tops.push_back(top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/tippe_top.yaml").model.top);
  return tops;
}

using Key = std::array<double, 3>;
Key key(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// Closed and consistently oriented: every directed edge occurs once and its reverse once (an edge-manifold,
// orientable surface without boundary); outward: the divergence-theorem volume is positive and equals the
// solid of revolution's (Pappus) times the N-gon's area ratio N sin(2 pi / N) / (2 pi), exact for this mesh.
TEST(TopMesh, BodyIsClosedOutwardAndFinite) {
  const int n = 32;
  for (const top_sim::Top& top : drawn_tops()) {
    top_sim_ros::TopShape shape = top_sim_ros::top_shape(top);
    if (!shape.cap.empty()) {  // a ball: its body and its painted cap are one closed sphere
      ASSERT_EQ(shape.cap.front(), shape.profile.back());
      shape.profile.insert(shape.profile.end(), shape.cap.begin() + 1, shape.cap.end());
    }
    const std::vector<Eigen::Vector3d> tri = top_sim_ros::revolve(shape.profile, n, 0.0, 2.0 * M_PI);
    ASSERT_EQ(tri.size() % 3, 0u);
    ASSERT_GT(tri.size(), 0u);
    std::map<std::pair<Key, Key>, int> edges;
    double volume = 0.0;
    for (std::size_t i = 0; i < tri.size(); i += 3) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(tri[i + k].allFinite()) << "mass " << top.mass;
        ++edges[{key(tri[i + k]), key(tri[i + (k + 1) % 3])}];
      }
      const Eigen::Vector3d normal = (tri[i + 1] - tri[i]).cross(tri[i + 2] - tri[i]);
      EXPECT_GT(normal.norm(), 0.0) << "degenerate triangle " << i / 3;
      volume += tri[i].dot(tri[i + 1].cross(tri[i + 2])) / 6.0;
    }
    for (const auto& e : edges) {
      EXPECT_EQ(e.second, 1) << "edge used twice in one direction";
      const auto reverse = edges.find({e.first.second, e.first.first});
      EXPECT_TRUE(reverse != edges.end() && reverse->second == 1) << "open or inconsistently oriented edge";
    }
    double pappus = 0.0;  // pi/3 sum (r0^2 + r0 r1 + r1^2)(z1 - z0) over the counter-clockwise profile
    for (std::size_t i = 0; i + 1 < shape.profile.size(); ++i) {
      const Eigen::Vector2d a = shape.profile[i], b = shape.profile[i + 1];
      pappus += M_PI / 3.0 * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) * (b.y() - a.y());
    }
    EXPECT_GT(volume, 0.0) << "triangles face inwards";
    EXPECT_NEAR(volume, pappus * n * std::sin(2.0 * M_PI / n) / (2.0 * M_PI), 1e-9 * pappus);
  }
}

// Sizes follow the model: the widest point is the disc with the top's axial inertia, the lowest the tip-sphere
// centre (f below the centre of mass); a heavier top of the same inertia is narrower.
TEST(TopMesh, SizesComeFromTheModel) {
  for (top_sim::Top top : drawn_tops()) {
    if (top.com_offset < 0.0) continue;  // a tippe top: TippeTopIsItsSphereWithAStem
    for (const double mass_factor : {1.0, 4.0}) {
      top.mass *= mass_factor;
      const top_sim_ros::TopShape shape = top_sim_ros::top_shape(top);
      double r_max = 0.0, z_min = 1.0, z_max = -1.0;
      for (const Eigen::Vector3d& p : top_sim_ros::revolve(shape.profile, 32, 0.0, 2.0 * M_PI)) {
        r_max = std::max(r_max, std::hypot(p.x(), p.y()));
        z_min = std::min(z_min, p.z());
        z_max = std::max(z_max, p.z());
      }
      EXPECT_NEAR(r_max, std::sqrt(2.0 * top.inertia_axial / top.mass), 1e-15);
      EXPECT_NEAR(z_min, -std::max(top.com_offset, 0.5 * shape.rim_height), 1e-15);
      EXPECT_NEAR(z_max, shape.stem_bottom, 1e-15);
      EXPECT_GE(shape.rim_height, 2.0 * top.tip_radius);
      EXPECT_GT(shape.stem_top, shape.stem_bottom);
      EXPECT_GT(shape.stem_radius, 0.0);
      EXPECT_LE(shape.stem_radius, 0.5 * r_max);
    }
  }
}

const visualization_msgs::Marker* find_marker(const visualization_msgs::MarkerArray& a, const std::string& ns) {
  for (const auto& m : a.markers)
    if (m.ns == ns) return &m;
  return nullptr;
}

// A tippe top (f < 0) is drawn as its sphere (centre |f| above the centre of mass, radius R) and nothing else: the
// stem's place is a cap of the sphere round the pole along +f_hat, in the stem's colour, so turning over shows and,
// the physics modelling only the sphere, nothing is drawn through the plane in any orientation. Its tip-sphere
// marker is deleted (the body is that sphere); the body is see-through (its trail runs under it).
TEST(TopMesh, TippeTopIsItsSphereWithItsStemPainted) {
  const top_sim::Top top = drawn_tops().back();
  ASSERT_LT(top.com_offset, 0.0);
  const top_sim_ros::TopShape shape = top_sim_ros::top_shape(top);
  const Eigen::Vector3d centre(0.0, 0.0, -top.com_offset);
  ASSERT_FALSE(shape.cap.empty());
  for (const auto* profile : {&shape.profile, &shape.cap})
    for (const Eigen::Vector3d& p : top_sim_ros::revolve(*profile, 32, 0.0, 2.0 * M_PI))
      EXPECT_NEAR((p - centre).norm(), top.tip_radius, 1e-12) << "off the sphere";
  EXPECT_NEAR(shape.profile.front().y(), -top.com_offset - top.tip_radius, 1e-15);
  EXPECT_NEAR(shape.cap.back().y(), -top.com_offset + top.tip_radius, 1e-15) << "the cap reaches the pole";
  EXPECT_EQ(shape.cap.back().x(), 0.0);
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(top_sim::Snapshot(), top, ros::Time(1.0), top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), a);
  EXPECT_EQ(find_marker(a, "tip")->action, visualization_msgs::Marker::DELETE);
  EXPECT_EQ(find_marker(a, "stem")->type, visualization_msgs::Marker::TRIANGLE_LIST);
  EXPECT_LT(find_marker(a, "body")->color.a, 1.0f);
  for (const auto& p : find_marker(a, "stem")->points)
    EXPECT_NEAR((Eigen::Vector3d(p.x, p.y, p.z) - centre).norm(), top.tip_radius, 1e-12);
}

// Body, stripe and stem live in the top frame, locked to it, so tf's plane -> top rotation (spin phase included)
// turns them; the stripe is a band off the axis on one side (body +x), raised above the body's surface.
TEST(Markers, BodyStripeAndStemAreDrawnInTheTopFrame) {
  const top_sim::Top top = drawn_tops().front();
  top_sim_ros::Frames frames;
  frames.top = "spin200/top";
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(top_sim::Snapshot(), top, ros::Time(1.0), frames, top_sim_ros::MarkerStyle(), a);
  std::set<int> ids;
  for (const auto& m : a.markers) {
    EXPECT_TRUE(ids.insert(m.id).second) << "id " << m.id << " used twice";
    EXPECT_LT(m.id, 16) << m.ns;
    EXPECT_GE(m.id, 0) << m.ns;
  }
  const double rb = top_sim_ros::top_shape(top).body_radius;
  for (const char* ns : {"body", "stripe", "stem"}) {
    const visualization_msgs::Marker* m = find_marker(a, ns);
    ASSERT_NE(m, nullptr) << ns;
    EXPECT_EQ(m->header.frame_id, "spin200/top") << ns;
    EXPECT_TRUE(m->frame_locked) << ns;
  }
  const visualization_msgs::Marker& stripe = *find_marker(a, "stripe");
  EXPECT_EQ(stripe.type, visualization_msgs::Marker::TRIANGLE_LIST);
  EXPECT_EQ(stripe.scale.x, 1.0);
  ASSERT_FALSE(stripe.points.empty());
  for (const auto& p : stripe.points) {
    EXPECT_GT(p.x, 0.0);                                         // one side only: the spin shows as its turning
    EXPECT_LE(std::abs(p.y), std::sin(0.5 * 0.5) * 1.05 * rb);  // within the stripe's half-width (0.25 rad)
  }
  EXPECT_GT(std::hypot(stripe.points.front().x, stripe.points.front().y), 0.0);
  double stripe_r_max = 0.0;
  for (const auto& p : stripe.points) stripe_r_max = std::max(stripe_r_max, std::hypot(p.x, p.y));
  EXPECT_GT(stripe_r_max, rb) << "the stripe must stand out of the rim, not inside it";
  EXPECT_LT(stripe_r_max, 1.05 * rb);
}

// The plane -> top transform carries the spin phase: over 2 ms at 200 rad/s the body x axis turns by about
// 0.4 rad about the figure axis (psi' = spin at a start without transverse rotation, physics.md section 2).
TEST(Transforms, TopFrameTurnsWithTheSpin) {
  top_sim::Simulator sim(top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml"));
  auto body_axes = [&]() {
    geometry_msgs::TransformStamped wp, pt;
    top_sim_ros::to_transforms(sim.pose(), ros::Time(1.0), top_sim_ros::Frames(), wp, pt);
    const auto& q = pt.transform.rotation;
    const Eigen::Quaterniond r(q.w, q.x, q.y, q.z);
    return std::make_pair(Eigen::Vector3d(r * Eigen::Vector3d::UnitX()), Eigen::Vector3d(r * Eigen::Vector3d::UnitZ()));
  };
  const auto [x0, f0] = body_axes();
  const double spin = sim.snapshot().spin, dt = 2.0e-3;
  ASSERT_TRUE(sim.advance_to(dt));
  const auto [x1, f1] = body_axes();
  const double turned = std::atan2(x0.cross(x1).dot(f1), x0.dot(x1));
  EXPECT_GT(std::abs(spin), 100.0);
  EXPECT_NEAR(turned, spin * dt, 0.01 * std::abs(spin * dt));
  EXPECT_LT((f1 - f0).norm(), 0.01) << "the figure axis barely moves in 2 ms";
}

TEST(TopCommand, StaticFrictionAndRestitutionAreCarriedUnvalidated) {
  top_sim::TopCommand m;
  m.set_static_friction = true;
  m.static_friction = 0.4;
  m.restitution = 0.7;  // not set: ignored
  std::string error;
  top_sim::Command c = command_from_message(m, error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(c.static_friction);
  EXPECT_EQ(*c.static_friction, 0.4);
  EXPECT_FALSE(c.restitution);
  EXPECT_FALSE(c.empty());

  m.set_static_friction = false;
  m.set_restitution = true;
  m.restitution = 1.5;  // out of [0, 1]: the adapter carries it, the core's validation rejects it
  c = command_from_message(m, error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(c.restitution);
  EXPECT_EQ(*c.restitution, 1.5);
  EXPECT_FALSE(c.static_friction);
  EXPECT_FALSE(c.inclination);
}

// The finite contact's and air's fields travel with their set_ flags; a negative value is the core's to refuse.
TEST(TopCommand, FiniteContactAndAirAreCarriedUnvalidated) {
  top_sim::TopCommand m;
  m.patch_radius = 1.0e-4;  // not set: ignored
  m.set_rolling_resistance = true;
  m.rolling_resistance = 2.0e-5;
  m.set_spin_drag = true;
  m.spin_drag = 3.0e-9;
  m.set_drag = true;
  m.drag = 4.0e-6;
  std::string error;
  top_sim::Command c = command_from_message(m, error);
  EXPECT_EQ(error, "");
  EXPECT_FALSE(c.patch_radius);
  ASSERT_TRUE(c.rolling_resistance && c.spin_drag && c.drag);
  EXPECT_EQ(*c.rolling_resistance, 2.0e-5);
  EXPECT_EQ(*c.spin_drag, 3.0e-9);
  EXPECT_EQ(*c.drag, 4.0e-6);

  top_sim::TopCommand only_patch;
  only_patch.set_patch_radius = true;
  only_patch.patch_radius = -1.0;
  c = command_from_message(only_patch, error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(c.patch_radius);
  EXPECT_EQ(*c.patch_radius, -1.0);
  EXPECT_NE(top_sim::validate(c, top_sim::Model()).find("patch_radius = -1"), std::string::npos)
      << top_sim::validate(c, top_sim::Model());
}

// A snapshot whose every field TopState carries has its own value (no two alike), so a swapped field shows.
top_sim::Snapshot distinct_snapshot() {
  top_sim::Snapshot s;
  double v = 0.0;
  auto next = [&v]() { return v += 0.1234567890123; };
  auto vec = [&]() { return Eigen::Vector3d(next(), next(), next()); };
  s.t = next(); s.alpha = next();
  s.tip_center = vec(); s.com = vec();
  s.orientation = Eigen::Quaterniond(next(), next(), next(), next());
  s.com_velocity = vec(); s.tip_velocity = vec(); s.contact_point = vec(); s.figure_axis = vec();
  s.angular_velocity = vec();
  s.spin = next(); s.has_rotor = true; s.rotor_spin = next(); s.slip = next(); s.mu = next();
  s.normal_force = next(); s.friction_force = vec(); s.phi = next();
  s.drilling_torque = next(); s.patch_radius = next();
  s.has_stationary_state = true; s.phi_star = next();
  s.regime = top_sim::Regime::precessing; s.contact_mode = top_sim::ContactMode::flight;
  s.gap = next(); s.energy = next(); s.dissipated_work = next(); s.energy_balance_residual = next();
  s.fault_message = "t = 1 s: fallen";
  s.touching = 0x80000005u;  // shapes 0, 2 and 31: every bit of the mask carried
  s.end_state = top_sim::EndState::lying_flat;
  s.end_message = "t = 1 s: end state lying_flat";
  return s;
}

// Snapshot -> TopState -> Snapshot gives every carried field back bit for bit (top_sim_bag's CSV is the node's state).
TEST(TopStateMsg, SnapshotRoundTripIsExact) {
  const top_sim::Snapshot a = distinct_snapshot();
  top_sim::TopState m;
  top_sim_ros::to_msg(a, ros::Time(3.0), "plane", m);
  std::string error;
  const top_sim::Snapshot b = top_sim_ros::to_snapshot(m, error);
  EXPECT_EQ(error, "");
  for (const top_sim::TrajectoryColumn& c : top_sim::trajectory_columns())  // every CSV column, exactly
    EXPECT_EQ(c.value(b), c.value(a)) << c.name;
  EXPECT_EQ(b.tip_center, a.tip_center);
  EXPECT_EQ(b.orientation.coeffs(), a.orientation.coeffs());
  EXPECT_EQ(b.tip_velocity.z(), a.tip_velocity.z());
  EXPECT_EQ(b.contact_point.z(), a.contact_point.z());
  EXPECT_EQ(b.friction_force, a.friction_force);
  EXPECT_EQ(b.has_rotor, a.has_rotor);
  EXPECT_EQ(b.normal_force, a.normal_force);
  EXPECT_EQ(b.drilling_torque, a.drilling_torque);
  EXPECT_EQ(b.patch_radius, a.patch_radius);
  EXPECT_EQ(b.has_stationary_state, a.has_stationary_state);
  EXPECT_EQ(b.phi_star, a.phi_star);
  EXPECT_EQ(b.dissipated_work, a.dissipated_work);
  EXPECT_EQ(b.regime, a.regime);
  EXPECT_EQ(b.contact_mode, a.contact_mode);
  EXPECT_EQ(b.fault_message, a.fault_message);
  EXPECT_EQ(b.fault, top_sim::ContactFault::none) << "TopState has no fault kind: none, with the text kept";
  EXPECT_EQ(b.touching, a.touching);
  EXPECT_EQ(m.end_state, "lying_flat");
  EXPECT_EQ(b.end_state, a.end_state);
  EXPECT_EQ(b.end_message, a.end_message);
  top_sim::TopState again;  // and back: the same message
  top_sim_ros::to_msg(b, ros::Time(3.0), "plane", again);
  EXPECT_TRUE(again == m);
}

TEST(TopStateMsg, BadCodesAndNonFiniteNumbersAreErrors) {
  top_sim::TopState m;
  m.regime = 15;
  std::string error;
  top_sim_ros::to_snapshot(m, error);
  EXPECT_EQ(error, "regime = 15: must be a code in 0..14");
  m.regime = top_sim::TopState::SLEEPING;
  m.contact_mode = 3;
  top_sim_ros::to_snapshot(m, error);
  EXPECT_EQ(error, "contact_mode = 3: must be a code in 0..2");
  m.contact_mode = top_sim::TopState::ROLLING;
  m.pose.position.y = std::numeric_limits<double>::quiet_NaN();
  top_sim_ros::to_snapshot(m, error);
  EXPECT_EQ(error, "com_y = nan: must be finite");
  m.pose.position.y = 0.0;
  m.friction_force.x = std::numeric_limits<double>::infinity();  // not a CSV column
  top_sim_ros::to_snapshot(m, error);
  EXPECT_NE(error.find("friction_force"), std::string::npos) << error;
  m.friction_force.x = 0.0;
  top_sim_ros::to_snapshot(m, error);
  EXPECT_EQ(error, "");
  m.end_state = "lying_down";
  top_sim_ros::to_snapshot(m, error);
  EXPECT_EQ(error, "end_state = 'lying_down': must be empty or one of lying_flat, at_rest, fallen");
  m.end_state = "";
  EXPECT_EQ(top_sim_ros::to_snapshot(m, error).end_state, top_sim::EndState::none);
  EXPECT_EQ(error, "");
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

// The label floats above the top and above top_sim_interactive's controls (control_layout.hpp): two lines of text
// centred on its position stay clear of the controls' highest point.
TEST(Markers, LabelIsAboveTheControls) {
  for (const top_sim::Top& top : drawn_tops()) {
    visualization_msgs::MarkerArray a;
    top_sim_ros::to_markers(top_sim::Snapshot(), top, ros::Time(1.0), top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), a);
    const auto& label = find_marker_or_fail(a, "label");
    EXPECT_GE(label.pose.position.z - label.scale.z, top_sim_ros::control_layout::kTop) << "mass " << top.mass;
  }
}

// ---- A body drawn from its contact shapes (top.shapes, physics.md section 13; top_mesh.hpp, shape_mesh).

namespace {

top_sim::Scene disc_fixture(const std::string& name) {
  return top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/../test/ros/scenes/" + name);
}

Eigen::Vector3d in_plane(const top_sim::Snapshot& s, const geometry_msgs::Point& p) {
  return s.com + s.orientation.normalized() * Eigen::Vector3d(p.x, p.y, p.z);
}

// The circle the touching tyre's edge draws (its outermost points at the least or greatest top-frame z), plane frame:
// centre, unit normal (the top frame's z) and radius; every point of the edge checked on it to 1e-12 m.
struct Ring {
  Eigen::Vector3d centre, normal;
  double radius = 0.0;
};
Ring drawn_ring(const top_sim::Snapshot& s, const visualization_msgs::Marker& band, bool lower) {
  double z = lower ? INFINITY : -INFINITY;
  for (const auto& p : band.points) z = lower ? std::min(z, p.z) : std::max(z, p.z);
  double outer = 0.0;  // the tyre's face at that z reaches in from the edge: the edge is its outermost circle
  for (const auto& p : band.points)
    if (p.z == z) outer = std::max(outer, std::hypot(p.x, p.y));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> edge;
  for (const auto& p : band.points)
    if (p.z == z && std::hypot(p.x, p.y) > outer - 1e-12) edge.emplace_back(p.x, p.y, p.z);
  for (const auto& p : edge) sum += p;
  Ring r;
  const Eigen::Vector3d centre = sum / static_cast<double>(edge.size());
  r.radius = (edge.front() - centre).norm();
  for (const auto& p : edge) EXPECT_NEAR((p - centre).norm(), r.radius, 1e-12);
  r.centre = s.com + s.orientation.normalized() * centre;
  r.normal = s.orientation.normalized() * Eigen::Vector3d::UnitZ();
  return r;
}

// The drawn disc against the rim: the band's edge is the rim (radius, centre at the centre of mass, normal f_hat),
// its lowest point on the plane and through the contact point, and no drawn point of the body below the plane.
void expect_disc_on_plane(const top_sim::Snapshot& s, const visualization_msgs::MarkerArray& a, bool lower_edge) {
  const visualization_msgs::Marker& band = find_marker_or_fail(a, "touching");
  ASSERT_EQ(band.action, visualization_msgs::Marker::ADD);
  ASSERT_FALSE(band.points.empty());
  const Ring ring = drawn_ring(s, band, lower_edge);
  EXPECT_NEAR(ring.radius, 0.04, 1e-12);
  EXPECT_LT((ring.centre - s.com).norm(), 1e-12) << "the rim is centred on the centre of mass (offset 0)";
  EXPECT_GT(ring.normal.dot(s.figure_axis), 1.0 - 1e-12) << "the disc's normal is f_hat";
  const double lowest = ring.centre.z() - ring.radius * std::sqrt(std::max(0.0, 1.0 - ring.normal.z() * ring.normal.z()));
  EXPECT_NEAR(lowest, 0.0, 1e-9) << "the rim's lowest point on the plane";
  EXPECT_NEAR((s.contact_point - ring.centre).norm(), ring.radius, 1e-9) << "the contact point on the drawn rim";
  EXPECT_NEAR((s.contact_point - ring.centre).dot(ring.normal), 0.0, 1e-9);
  for (const char* ns : {"body", "touching"})
    for (const auto& p : find_marker_or_fail(a, ns).points) ASSERT_GT(in_plane(s, p).z(), -1e-9) << ns;
}

}  // namespace

// The rolling disc of test/ros/scenes/disc_rolling.yaml: its rim drawn where the core has it, touching, the
// disc's thickness on the side away from the plane, whichever way f_hat points.
TEST(ShapeMarkers, RollingDiscIsDrawnWhereItsRimIs) {
  top_sim::Simulator sim(disc_fixture("disc_rolling.yaml"));
  ASSERT_TRUE(sim.advance_to(0.37));
  top_sim::Snapshot s = sim.snapshot();
  ASSERT_EQ(s.touching, 1u);
  ASSERT_NEAR(std::acos(s.figure_axis.z()), 0.5, 1e-6);
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(s, sim.model().top, sim.model().shapes, ros::Time(1.0), top_sim_ros::Frames(),
                          top_sim_ros::MarkerStyle(), a);
  expect_disc_on_plane(s, a, true);
  for (const char* ns : {"tip", "stem"}) EXPECT_EQ(find_marker_or_fail(a, ns).action, visualization_msgs::Marker::DELETE);
  for (const char* ns : {"body", "stripe", "spin"})
    EXPECT_EQ(find_marker_or_fail(a, ns).action, visualization_msgs::Marker::ADD) << ns;

  // The same disc turned over (f_hat -> -f_hat, the rim in the same place): its thickness goes the other way.
  s.orientation = s.orientation.normalized() * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  s.figure_axis = -s.figure_axis;
  top_sim_ros::to_markers(s, sim.model().top, sim.model().shapes, ros::Time(1.0), top_sim_ros::Frames(),
                          top_sim_ros::MarkerStyle(), a);
  expect_disc_on_plane(s, a, false);
}

// The dropped disc (test/ros/scenes/disc_dropped.yaml) at its end, lying flat: still drawn on its rim, on the plane.
TEST(ShapeMarkers, DroppedDiscLiesFlatOnThePlaneAtItsEnd) {
  top_sim::Simulator sim(disc_fixture("disc_dropped.yaml"));
  sim.advance_to(5.0);
  ASSERT_EQ(sim.end_state(), top_sim::EndState::lying_flat);
  const top_sim::Snapshot s = sim.snapshot();
  ASSERT_EQ(s.touching, 1u);
  visualization_msgs::MarkerArray a;
  top_sim_ros::to_markers(s, sim.model().top, sim.model().shapes, ros::Time(1.0), top_sim_ros::Frames(),
                          top_sim_ros::MarkerStyle(), a);
  expect_disc_on_plane(s, a, s.figure_axis.z() >= 0.0);
  double highest = 0.0;
  for (const auto& p : find_marker_or_fail(a, "body").points) highest = std::max(highest, in_plane(s, p).z());
  const double t = top_sim_ros::rim_thickness(sim.model().top, sim.model().shapes, 0);
  EXPECT_NEAR(t, top_sim_ros::kThinRim * 0.04, 1e-15) << "a thin disc's inertia gives no thickness";
  EXPECT_NEAR(highest, t, 1e-5) << "lying flat: the drawn disc from the plane up to its thickness";
}

// The highlight follows Snapshot::touching: the touching shapes in white (a sphere whole, a rim's tyre), the
// others in the body's colour, nothing highlighted in flight. A top of tip sphere and crown rim, built by hand.
TEST(ShapeMarkers, TouchingHighlightFollowsTouching) {
  top_sim::Top top = small_top();
  top_sim::ShapeSet shapes;
  shapes.shape[0] = {top_sim::ShapeKind::sphere, -0.010, 1.5e-3};
  shapes.shape[1] = {top_sim::ShapeKind::rim, 0.004, 0.02};
  shapes.count = 2;
  shapes.active = top_sim::shapes_active(shapes);
  const double t = top_sim_ros::rim_thickness(top, shapes, 1);
  top_sim::Snapshot s;
  s.orientation = Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitY());
  s.figure_axis = s.orientation * Eigen::Vector3d::UnitZ();
  std::map<std::uint32_t, std::size_t> body_points;
  for (std::uint32_t touching : {0u, 1u, 2u, 3u}) {
    s.touching = touching;
    visualization_msgs::MarkerArray a;
    top_sim_ros::to_markers(s, top, shapes, ros::Time(1.0), top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), a);
    const visualization_msgs::Marker& lit = find_marker_or_fail(a, "touching");
    body_points[touching] = find_marker_or_fail(a, "body").points.size();
    const top_sim_ros::Rgb body = top_sim_ros::body_colour(s, top_sim_ros::ColorBy::regime);
    EXPECT_EQ(find_marker_or_fail(a, "body").color.g, body.g) << "the rest of the body keeps the regime's colour";
    if (touching == 0) {
      EXPECT_EQ(lit.action, visualization_msgs::Marker::DELETE) << "in flight nothing touches";
      continue;
    }
    ASSERT_EQ(lit.action, visualization_msgs::Marker::ADD) << touching;
    EXPECT_FALSE(same(lit.color, find_marker_or_fail(a, "body").color)) << "the highlight stands out";
    bool on_tip = false, on_crown = false;
    for (const auto& p : lit.points) {
      const Eigen::Vector3d q(p.x, p.y, p.z);
      const bool tip = std::abs((q - Eigen::Vector3d(0, 0, -0.010)).norm() - 1.5e-3) < 1e-12;
      const double r = std::hypot(q.x(), q.y());  // the crown's tyre: its edge and the outer kTyre of its faces
      const bool crown = r > (1.0 - top_sim_ros::kTyre) * 0.02 - 1e-12 && r < 0.02 + 1e-12 &&
                         q.z() >= 0.004 - 1e-12 && q.z() <= 0.004 + t + 1e-12;
      EXPECT_TRUE(tip || crown) << "a highlighted point on neither shape: " << q.transpose();
      on_tip |= tip;
      on_crown |= crown;
    }
    EXPECT_EQ(on_tip, (touching & 1u) != 0) << touching;
    EXPECT_EQ(on_crown, (touching & 2u) != 0) << touching;
  }
  // What is highlighted leaves the body's mesh: the shares add up whatever touches.
  EXPECT_GT(body_points[0], body_points[1]);
  EXPECT_GT(body_points[1], body_points[3]);
  EXPECT_GT(body_points[2], body_points[3]);
}

// One sphere given as top.shapes is the ordinary tip sphere: drawn exactly as the same top given by tip_radius and
// com_offset (every marker, every point and colour), no "touching" marker.
TEST(ShapeMarkers, TipSphereAloneIsTheOrdinaryTop) {
  const std::string body = "top: {mass: 0.025, inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6, ";
  const std::string rest = "}\nplane: {inclination: 0.1}\nfriction: {law: coulomb, mu: 0.3}\n"
                           "initial: {start: tilted, tilt: 0.1, spin: 150.0}\n";
  top_sim::Simulator shaped(top_sim::parse_scene_text(
      body + "shapes: [{sphere: {offset: -0.01, radius: 1.5e-3}}]" + rest, "shaped.yaml"));
  top_sim::Simulator plain(top_sim::parse_scene_text(body + "tip_radius: 1.5e-3, com_offset: 0.01" + rest,
                                                     "plain.yaml"));
  ASSERT_FALSE(shaped.model().shapes.active);
  ASSERT_TRUE(shaped.advance_to(0.2));
  ASSERT_TRUE(plain.advance_to(0.2));
  visualization_msgs::MarkerArray a, b;
  top_sim_ros::to_markers(shaped.snapshot(), shaped.model().top, shaped.model().shapes, ros::Time(1.0),
                          top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), a);
  top_sim_ros::to_markers(plain.snapshot(), plain.model().top, ros::Time(1.0), top_sim_ros::Frames(),
                          top_sim_ros::MarkerStyle(), b);
  ASSERT_EQ(a.markers.size(), b.markers.size());
  for (std::size_t i = 0; i < a.markers.size(); ++i) {
    EXPECT_EQ(a.markers[i].ns, b.markers[i].ns);
    EXPECT_NE(a.markers[i].ns, "touching");
    EXPECT_EQ(a.markers[i].action, b.markers[i].action) << a.markers[i].ns;
    EXPECT_TRUE(same(a.markers[i].color, b.markers[i].color)) << a.markers[i].ns;
    ASSERT_EQ(a.markers[i].points.size(), b.markers[i].points.size()) << a.markers[i].ns;
    for (std::size_t k = 0; k < a.markers[i].points.size(); ++k)
      EXPECT_TRUE(a.markers[i].points[k].x == b.markers[i].points[k].x &&
                  a.markers[i].points[k].y == b.markers[i].points[k].y &&
                  a.markers[i].points[k].z == b.markers[i].points[k].z) << a.markers[i].ns << " point " << k;
  }
}

// The dropped disc at its end: the label says the end state where a running top has its regime and mode.
TEST(ShapeMarkers, LabelShowsTheEndState) {
  top_sim::Simulator sim(disc_fixture("disc_dropped.yaml"));
  EXPECT_EQ(top_sim_ros::status_text("d", sim.snapshot()).find("end:"), std::string::npos) << "running";
  sim.advance_to(5.0);
  ASSERT_EQ(sim.end_state(), top_sim::EndState::lying_flat);
  const std::string text = top_sim_ros::status_text("d", sim.snapshot(), "\n");
  EXPECT_EQ(text.rfind("d: end: lying_flat at t = ", 0), 0u) << text;
  EXPECT_EQ(text.find("phi"), std::string::npos) << "nothing of the motion that stopped: " << text;
}

namespace {

// The interactive controls rest beside the body, out of its way (issue 46): Euler's disk reaches twice its shapes'
// reach from its contact point, and the controls rest beyond that; an ordinary top's stay where they were (5 cm).
TEST(ControlLayout, ControlsRestBesideTheBody) {
  const top_sim::Scene disk = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/euler_disk.yaml");
  const double reach = top_sim_ros::reach_from_contact(disk.model.top, disk.model.shapes);
  EXPECT_GT(reach, 2.0 * 0.0375);  // the disc's diameter at least
  EXPECT_GE(top_sim_ros::control_layout::offset_x(reach) - 0.5 * top_sim_ros::control_layout::kScale, reach);
  const top_sim::Scene top = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml");
  const double top_reach = top_sim_ros::reach_from_contact(top.model.top, top.model.shapes);
  EXPECT_GE(top_sim_ros::control_layout::offset_x(top_reach) - 0.5 * top_sim_ros::control_layout::kScale, top_reach);
  EXPECT_NEAR(top_sim_ros::control_layout::offset_x(top_reach), top_sim_ros::control_layout::kOffsetX, 0.005);
}

}  // namespace
