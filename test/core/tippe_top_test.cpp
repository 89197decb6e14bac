// The tippe top (config/scenes/tippe_top*.yaml; docs/physics.md, "The tippe top"): a sphere whose centre of mass
// lies below its centre. Jellett's integral lambda = -L . a (L about the centre of mass, a from the centre of mass
// to the contact point) is conserved by a contact force at the contact point with no drilling torque; the
// regularised-Coulomb top turns over and ends spinning about the vertical at the spin lambda fixes; with stick
// allowed it rolls, dissipates nothing and never turns over.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

top_sim::Scene tippe(const char* name) {
  return top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/" + name);
}

// lambda = -L . a with L = I_d omega + (I_f - I_d)(omega . f) f about the centre of mass and a from the centre of
// mass to the sphere's lowest point (the contact point in contact; in flight the point that will touch).
double jellett(const top_sim::Top& top, const top_sim::Snapshot& s) {
  const Eigen::Vector3d& w = s.angular_velocity;
  const Eigen::Vector3d& f = s.figure_axis;
  const Eigen::Vector3d L = top.inertia_transverse * w + (top.inertia_axial - top.inertia_transverse) * w.dot(f) * f;
  const Eigen::Vector3d lowest = s.tip_center - Eigen::Vector3d(0.0, 0.0, top.tip_radius);
  return -L.dot(lowest - s.com);
}

double tilt(const top_sim::Snapshot& s) { return std::acos(std::max(-1.0, std::min(1.0, s.figure_axis.z()))); }

}  // namespace

// Slipping throughout (regularised Coulomb): lambda holds to 1e-8 relative every 50 ms of 12 s; the top turns over
// (tilt > pi - 0.1) and its vertical angular velocity approaches lambda's value for the inverted sphere with
// I_f = I_d: omega_z = spin0 (R cos theta0 + f) / (R - f) (f < 0), within 1 %.
TEST(TippeTop, InvertsConservingJellettsIntegral) {
  const top_sim::Scene scene = tippe("tippe_top.yaml");
  top_sim::Simulator sim(scene);
  const top_sim::Top& top = scene.model.top;
  const double lambda0 = jellett(top, sim.snapshot());
  double worst = 0.0;
  for (int k = 1; k <= 240; ++k) {
    ASSERT_TRUE(sim.advance_to(0.05 * k)) << sim.fault_message();
    const top_sim::Snapshot s = sim.snapshot();
    EXPECT_EQ(s.contact_mode, top_sim::ContactMode::slipping) << "t = " << s.t;
    worst = std::max(worst, std::abs(jellett(top, s) - lambda0) / std::abs(lambda0));
  }
  EXPECT_LT(worst, 1e-8) << "Jellett's integral drifted";
  const top_sim::Snapshot end = sim.snapshot();
  EXPECT_GT(tilt(end), M_PI - 0.1) << "the tippe top must turn over";
  const double R = top.tip_radius, f = top.com_offset, theta0 = scene.initial.tilt, spin0 = scene.initial.spin;
  const double omega_z = spin0 * (R * std::cos(theta0) + f) / (R - f);
  EXPECT_NEAR(end.angular_velocity.z(), omega_z, 0.01 * std::abs(omega_z));
  EXPECT_NEAR(end.spin, -omega_z, 0.01 * std::abs(omega_z)) << "upside down: omega . f_hat = -omega_z";
}

// Dropped from 1 cm with restitution 0.5: flight (no torque), impacts (an impulse at the contact point) and slipping;
// lambda holds to 1e-8 through all of them (measured 1e-9 over 3 s).
TEST(TippeTop, JellettsIntegralHoldsThroughFlightAndImpacts) {
  top_sim::Scene scene = tippe("tippe_top.yaml");
  scene.initial.gap = 0.01;
  scene.model.contact.restitution = 0.5;
  top_sim::Simulator sim(scene);
  const top_sim::Top& top = scene.model.top;
  const double lambda0 = jellett(top, sim.snapshot());
  ASSERT_EQ(sim.contact_mode(), top_sim::ContactMode::flight);
  double worst = 0.0;
  bool touched = false;
  for (int k = 1; k <= 300; ++k) {
    ASSERT_TRUE(sim.advance_to(0.01 * k)) << sim.fault_message();
    touched = touched || sim.contact_mode() != top_sim::ContactMode::flight;
    worst = std::max(worst, std::abs(jellett(top, sim.snapshot()) - lambda0) / std::abs(lambda0));
  }
  EXPECT_TRUE(touched) << "the drop must land";
  EXPECT_GE(sim.mode_switch_count(), 2u) << "lift-off and touchdown: at least one hop";
  EXPECT_LT(worst, 1e-8);
}

// The regime a tippe top publishes is its own: upright at the start (tilt 0.1), inverting while the tilt moves
// through the middle, inverted at the end (tilt > pi - 0.5); the rolling one stays upright. No sleeping-top regime.
TEST(TippeTop, RegimeFollowsTheTurnOver) {
  top_sim::Simulator sim(tippe("tippe_top.yaml"));
  EXPECT_TRUE(sim.advance_to(0.01));
  EXPECT_EQ(sim.snapshot().regime, top_sim::Regime::upright);
  bool inverting = false;
  for (int k = 1; k <= 120 && !inverting; ++k) {
    ASSERT_TRUE(sim.advance_to(0.1 * k));
    inverting = sim.snapshot().regime == top_sim::Regime::inverting;
  }
  EXPECT_TRUE(inverting) << "no inverting phase";
  ASSERT_TRUE(sim.advance_to(12.0));
  EXPECT_EQ(sim.snapshot().regime, top_sim::Regime::inverted);
  top_sim::Simulator rolling(tippe("tippe_top_rolling.yaml"));
  ASSERT_TRUE(rolling.advance_to(5.0));
  EXPECT_EQ(rolling.snapshot().regime, top_sim::Regime::upright);
  EXPECT_STREQ(top_sim::to_string(top_sim::Regime::tumbling), "tumbling");
}

// Exact Coulomb with stick: the contact rolls within 0.1 s, the energy holds to 1e-9 relative while it rolls (no
// slip, no dissipation), lambda holds through the switches, and the top never turns over.
TEST(TippeTop, RollingTopNeverInverts) {
  const top_sim::Scene scene = tippe("tippe_top_rolling.yaml");
  top_sim::Simulator sim(scene);
  const top_sim::Top& top = scene.model.top;
  const double lambda0 = jellett(top, sim.snapshot());
  ASSERT_TRUE(sim.advance_to(0.1));
  ASSERT_EQ(sim.contact_mode(), top_sim::ContactMode::rolling);
  const double e0 = sim.snapshot().energy;
  double max_tilt = 0.0, e_drift = 0.0, l_drift = 0.0;
  for (int k = 1; k <= 490; ++k) {
    ASSERT_TRUE(sim.advance_to(0.1 + 0.01 * k)) << sim.fault_message();
    const top_sim::Snapshot s = sim.snapshot();
    ASSERT_EQ(s.contact_mode, top_sim::ContactMode::rolling) << "t = " << s.t;
    max_tilt = std::max(max_tilt, tilt(s));
    e_drift = std::max(e_drift, std::abs(s.energy - e0) / e0);
    l_drift = std::max(l_drift, std::abs(jellett(top, s) - lambda0) / std::abs(lambda0));
  }
  EXPECT_LT(e_drift, 1e-9);
  EXPECT_LT(l_drift, 1e-8);
  EXPECT_LT(max_tilt, 0.2) << "a rolling tippe top does not turn over";
}
