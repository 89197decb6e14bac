// The stationary ("sleeping") state against physics.md section 5, and that it is an equilibrium of the full
// dynamics. Expected values are the formulas of physics.md evaluated here, never the solver's own output.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_util.hpp"
#include "top_sim/contact.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace {

using namespace top_sim;
using top_sim_test::paper_slip_star;

const Eigen::Vector3d kN = Eigen::Vector3d::UnitZ();

Model paper_model(double alpha, double mu_c = 0.25, double s_c = 0.6) {
  Model m;
  m.plane = make_plane(alpha, 9.81);
  m.friction.kind = FrictionLawKind::paper;
  m.friction.mu_c = mu_c;
  m.friction.s_c = s_c;
  return m;
}

Eigen::Vector3d g_hat(const Model& m) { return m.plane.g_plane.normalized(); }

// physics.md section 5: f_hat* = -(R/f) n + f_g g_hat, f_g = -(R/f) cos(alpha) - sqrt(1 - (R sin(alpha)/f)^2).
Eigen::Vector3d f_hat_formula(const Model& m) {
  const double R = m.top.tip_radius, f = m.top.com_offset, a = m.plane.inclination;
  const double f_g = -(R / f) * std::cos(a) - std::sqrt(1.0 - std::pow(R * std::sin(a) / f, 2));
  return -(R / f) * kN + f_g * g_hat(m);
}

// Checks every closed-form relation of section 5 for one model and signed spin.
void check_section5(const Model& m, double spin, double s_expected) {
  SCOPED_TRACE("alpha = " + std::to_string(m.plane.inclination) + ", spin = " + std::to_string(spin));
  const StationaryState st = stationary_state(m, spin);
  ASSERT_TRUE(st.exists) << st.reason;
  ASSERT_TRUE(st.phi_defined) << st.reason;
  const double R = m.top.tip_radius, f = m.top.com_offset, alpha = m.plane.inclination;

  // s* is the stable root; 1e-14: a square root and a few products.
  EXPECT_NEAR(st.slip, s_expected, 1e-14);
  // mu(s*) = tan(alpha): the friction balances the in-plane weight (rounding only).
  EXPECT_NEAR(friction_coefficient(m.friction, st.slip), std::tan(alpha), 1e-14);

  // The unnormalised formula is already a unit vector (|.|^2 = R^2/f^2 + 1 - R^2/f^2 = 1 identically).
  const Eigen::Vector3d f_formula = f_hat_formula(m);
  EXPECT_NEAR(f_formula.norm(), 1.0, 1e-15);
  EXPECT_NEAR(st.f_hat.norm(), 1.0, 1e-15);
  EXPECT_LT((st.f_hat - f_formula).norm(), 1e-15);

  // Centre of mass vertically above the contact: r_cm - r_t = R n + f f_hat* parallel to -g_hat.
  const Eigen::Vector3d lever = R * kN + f * st.f_hat;
  EXPECT_LT(lever.cross(g_hat(m)).norm(), 1e-15);  // a ~1e-2 m lever: rounding is ~1e-18 m
  EXPECT_LT(lever.dot(g_hat(m)), 0.0);                   // above, not below

  // omega* = spin f_hat*.
  EXPECT_LT((st.omega - spin * f_formula).norm(), 1e-13 * std::abs(spin));

  // phi*: tan(phi*/2) = s* for spin > 0; pi - 2 atan(s*) for spin < 0.
  const double phi_plus = 2.0 * std::atan(s_expected);
  EXPECT_NEAR(st.phi, spin > 0 ? phi_plus : M_PI - phi_plus, 1e-14);

  // Velocities: v_h = R |omega*| |f_hat* x n| along sign(omega*) h; v_d = v_h tan(2 atan s*) downhill (-e_y).
  const double v_h = R * std::abs(spin) * f_formula.cross(kN).norm();
  const double v_d = v_h * std::tan(phi_plus);
  EXPECT_NEAR(st.rolling_speed, v_h, 1e-14 * v_h);
  EXPECT_NEAR(st.sliding_speed, v_d, 1e-13 * v_d);
  EXPECT_NEAR(st.velocity.x(), (spin > 0 ? 1.0 : -1.0) * v_h, 1e-14 * v_h);
  EXPECT_NEAR(-st.velocity.y(), v_d, 1e-13 * v_d);
  // The travel angle of u* from h towards downhill is phi* itself.
  EXPECT_NEAR(std::atan2(-st.velocity.y(), st.velocity.x()), st.phi, 1e-14);

  // The contact kinematics of section 3 at (u*, omega*) give back s* (v_eps made negligible: 1e-16 m/s).
  Model exact = m;
  exact.regularization_speed = 1e-16;
  const ContactKinematics k =
      contact_kinematics(exact, Eigen::Vector3d(st.velocity.x(), st.velocity.y(), 0.0), st.omega);
  EXPECT_NEAR(k.slip, s_expected, 1e-13);
  // The material velocity at the contact slides straight downhill (v_t = v_d along -e_y).
  EXPECT_LT(std::abs(k.v_t.x()), 1e-15 + 1e-13 * v_d);
}

TEST(StationarySolver, PaperLawMatchesSection5) {
  for (double alpha : {0.02, 0.05, 0.1, 0.15, 0.2, 0.24})
    for (double spin : {200.0, -200.0, 5.0, 5000.0})
      check_section5(paper_model(alpha), spin, paper_slip_star(alpha, 0.25, 0.6));
}

TEST(StationarySolver, OtherTopsAndNegativeInclination) {
  Model steel = paper_model(0.12, 0.2, 0.7);
  steel.top.mass = 0.04;
  steel.top.tip_radius = 1.0e-3;
  steel.top.com_offset = 8.0e-3;
  check_section5(steel, 150.0, paper_slip_star(0.12, 0.2, 0.7));
  Model blunt = paper_model(0.1);
  blunt.top.tip_radius = 6.0e-3;  // R/f = 0.6: a strongly tilted sleeping axis
  check_section5(blunt, 300.0, paper_slip_star(0.1, 0.25, 0.6));
}

TEST(StationarySolver, PaperLawBranchesAndCriticalInclination) {
  // s_c = 0.4: the unstable root s_c (1 + sqrt(1 - tan(alpha)/mu_c)) lies inside [0, 1].
  const Model m = paper_model(0.1, 0.25, 0.4);
  const double q = std::sqrt(1.0 - std::tan(0.1) / 0.25);
  const auto roots = slip_roots(m.friction, std::tan(0.1));
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].s, 0.4 * (1.0 - q), 1e-14);
  EXPECT_TRUE(roots[0].stable);  // d mu/ds > 0 below s_c
  EXPECT_NEAR(roots[1].s, 0.4 * (1.0 + q), 1e-14);
  EXPECT_FALSE(roots[1].stable);  // d mu/ds < 0 above s_c
  const StationaryState st = stationary_state(m, 200.0);
  ASSERT_TRUE(st.exists);
  EXPECT_NEAR(st.slip, 0.4 * (1.0 - q), 1e-14);  // the solver picks the stable branch
  EXPECT_NEAR(st.slip_unstable, 0.4 * (1.0 + q), 1e-14);

  // With s_c = 0.6 at alpha 0.1 the second root 0.6 (1 + q) > 1 is outside [0, 1]: no unstable state.
  const StationaryState st6 = stationary_state(paper_model(0.1), 200.0);
  EXPECT_GT(0.6 * (1.0 + q), 1.0);
  EXPECT_LT(st6.slip_unstable, 0.0);

  // alpha_c = atan(mu_c); existence flips across it (1e-9 rad on either side: far above rounding).
  const double alpha_c = std::atan(0.25);
  EXPECT_NEAR(critical_inclination(m.friction), alpha_c, 1e-15);
  EXPECT_TRUE(stationary_state(paper_model(alpha_c - 1e-9), 200.0).exists);
  const StationaryState above = stationary_state(paper_model(alpha_c + 1e-9), 200.0);
  EXPECT_FALSE(above.exists);
  EXPECT_NE(above.reason.find("alpha_c"), std::string::npos) << above.reason;
  EXPECT_FALSE(stationary_state(paper_model(-(alpha_c + 1e-3)), 200.0).exists);  // mirror inclination
  // At alpha_c itself both branches merge at s = s_c (the square root vanishes).
  EXPECT_NEAR(paper_slip_star(alpha_c, 0.25, 0.6), 0.6, 1e-7);
}

TEST(StationarySolver, NoStateWhenTheCentreOfMassCannotBeAboveTheContact) {
  // R sin(alpha) > f: R = 20 mm, f = 10 mm, alpha = 0.6 (R sin = 11.3 mm). mu_c = 1 so friction alone would allow it.
  Model m = paper_model(0.6, 1.0, 0.6);
  m.top.tip_radius = 0.02;
  m.top.com_offset = 0.01;
  const StationaryState st = stationary_state(m, 200.0);
  EXPECT_FALSE(st.exists);
  EXPECT_NE(st.reason.find("R sin(alpha)"), std::string::npos) << st.reason;
  // Control: R = 15 mm gives R sin(alpha) = 8.5 mm < f, and the state exists.
  m.top.tip_radius = 0.015;
  EXPECT_TRUE(stationary_state(m, 200.0).exists);
}

// derivative() vanishes at the exact stationary state: u' (scale g), f_hat' (scale |omega|) and omega'
// (scale of the gravity torque m g |rho| / I_d) to 1e-12 relative; N = m g cos(alpha).
void check_equilibrium(Model m, double spin, const std::string& what) {
  SCOPED_TRACE(what + ", spin = " + std::to_string(spin));
  // v_eps shifts the balance by ~v_eps / |u| ~ 1e-8 relative (physics.md section 5); 1e-16 m/s removes it.
  m.regularization_speed = 1e-16;
  const StationaryState st = stationary_state(m, spin);
  ASSERT_TRUE(st.exists) << st.reason;
  const StateVector y = stationary_state_vector(m, st, spin, Eigen::Vector2d(0.3, -0.2), 0.0);
  StateVector dy{};
  derivative(m, ContactMode::slipping, y, dy);
  Dynamics dyn;
  evaluate_dynamics(m, ContactMode::slipping, y, dyn);
  const double g = m.plane.gravity, alpha = m.plane.inclination;
  const double lever = (m.top.tip_radius * kN + m.top.com_offset * st.f_hat).norm();
  const double torque_scale = m.top.mass * g * lever / m.top.inertia_transverse;
  EXPECT_LT(std::hypot(dy[idx::u], dy[idx::u + 1]), 1e-12 * g);
  EXPECT_LT(Eigen::Vector3d(dy[idx::f], dy[idx::f + 1], dy[idx::f + 2]).norm(), 1e-12 * std::abs(spin));
  EXPECT_LT(Eigen::Vector3d(dy[idx::omega], dy[idx::omega + 1], dy[idx::omega + 2]).norm(), 1e-12 * torque_scale);
  EXPECT_NEAR(dyn.normal_force, m.top.mass * g * std::cos(alpha), 1e-12 * m.top.mass * g);
  // The position moves with u* and the friction dissipates mu N |v_t| = m g sin(alpha) v_d.
  EXPECT_NEAR(dy[idx::x], st.velocity.x(), 1e-15);
  EXPECT_NEAR(dyn.dissipation, m.top.mass * g * std::sin(alpha) * st.sliding_speed,
              1e-12 * m.top.mass * g * st.sliding_speed);
  EXPECT_GT(dyn.margins.painleve, 0.0);
  EXPECT_GT(dyn.margins.lift, 0.0);
}

TEST(StationarySolver, ExactStateIsAnEquilibriumOfTheFullDynamics) {
  for (double alpha : {0.02, 0.1, 0.2})
    for (double spin : {200.0, -200.0, 3000.0}) {
      check_equilibrium(paper_model(alpha), spin, "paper, constrained");
      Model s = paper_model(alpha);
      s.normal_force = NormalForceModel::static_approximation;
      check_equilibrium(s, spin, "paper, static");
    }
}

TEST(StationarySolver, TableAndLinearizedLawsSleepInTheirOwnBalance) {
  const double alpha = 0.1, t = std::tan(alpha);
  // Linearized mu0 + k (s - s0) = tan(alpha)  ->  s* = s0 + (tan(alpha) - mu0) / k.
  Model lin = paper_model(alpha);
  lin.friction.kind = FrictionLawKind::linearized;
  lin.friction.mu0 = 0.1;
  lin.friction.k = 1.0;
  lin.friction.s0 = 0.3;
  check_section5(lin, 200.0, 0.3 + (t - 0.1) / 1.0);
  check_equilibrium(lin, 200.0, "linearized");

  // Table (0, 0) - (0.5, 0.3) - (1, 0.2): rising segment gives s* = tan(alpha) / 0.6.
  Model tab = paper_model(alpha);
  tab.friction.kind = FrictionLawKind::table;
  tab.friction.points = {{0.0, 0.0}, {0.5, 0.3}, {1.0, 0.2}};
  check_section5(tab, -200.0, t / 0.6);
  check_equilibrium(tab, -200.0, "table");

  // At alpha 0.25 (tan 0.2553 > 0.2) the falling segment adds an unstable root: 0.3 - 0.2 (s - 0.5) = tan.
  const auto roots = slip_roots(tab.friction, std::tan(0.25));
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0].s, std::tan(0.25) / 0.6, 1e-14);
  EXPECT_TRUE(roots[0].stable);
  EXPECT_NEAR(roots[1].s, 0.5 + (0.3 - std::tan(0.25)) / 0.2, 1e-14);
  EXPECT_FALSE(roots[1].stable);
}

TEST(StationarySolver, PhiStarIsIndependentOfSpinMassInertiaRadiusAndOffset) {
  const Model base = paper_model(0.1);
  const double phi = stationary_state(base, 200.0).phi;
  // Section 5: phi* = 2 atan(s*) depends on alpha and the law only; rounding-level agreement expected.
  EXPECT_NEAR(phi, top_sim_test::paper_phi_star(0.1, 0.25, 0.6), 1e-14);
  for (double spin : {100.0, 400.0, 1.0, 1e4}) EXPECT_NEAR(stationary_state(base, spin).phi, phi, 1e-14);
  Model v = base;
  v.top.mass = 0.1;
  EXPECT_NEAR(stationary_state(v, 200.0).phi, phi, 1e-14);
  v = base;
  v.top.inertia_axial = 2e-6;
  v.top.inertia_transverse = 7e-6;
  EXPECT_NEAR(stationary_state(v, 200.0).phi, phi, 1e-14);
  v = base;
  v.top.tip_radius = 4e-3;
  EXPECT_NEAR(stationary_state(v, 200.0).phi, phi, 1e-14);
  v = base;
  v.top.com_offset = 0.03;
  EXPECT_NEAR(stationary_state(v, 200.0).phi, phi, 1e-14);
  // Reversing the spin maps phi* to pi - phi*.
  EXPECT_NEAR(stationary_state(base, -200.0).phi, M_PI - phi, 1e-14);
}

TEST(StationarySolver, ZeroTipRadiusHasNoDirectionOfTravel) {
  Model m = paper_model(0.1);
  m.top.tip_radius = 0.0;
  const StationaryState st = stationary_state(m, 200.0);
  // With R = 0 the sleeping top does not roll (v_h = 0), so phi* is undefined, with the reason given.
  EXPECT_FALSE(st.phi_defined);
  EXPECT_EQ(st.rolling_speed, 0.0);
  EXPECT_NE(st.reason.find("R = 0"), std::string::npos) << st.reason;
  EXPECT_TRUE(std::isfinite(st.phi) && st.f_hat.allFinite() && st.velocity.allFinite());
}

// The simulator keeps the spin-free part of the sleeping state per model (stationary_geometry): a sample must read
// the plane it is on, after a command and after a reset, in the same bits as a fresh solve at the sample's spin.
TEST(StationaryGeometry, ASampleReadsTheSleepingStateOfThePlaneItIsOn) {
  Simulator sim(load_scene(top_sim_test::scene_path("default")));
  auto fresh = [&sim] {
    const Snapshot s = sim.snapshot();
    return stationary_state(sim.model(), s.spin);
  };
  sim.advance_to(0.01);
  const double slip_01 = sim.stationary().slip;
  EXPECT_EQ(sim.stationary().phi, fresh().phi);
  EXPECT_EQ(sim.stationary().velocity, fresh().velocity);
  Command steeper;
  steeper.inclination = 0.2;
  ASSERT_EQ(sim.submit(steeper), "");
  sim.advance_to(0.02);
  EXPECT_EQ(sim.model().plane.inclination, 0.2);
  EXPECT_EQ(sim.stationary().phi, fresh().phi);
  EXPECT_EQ(sim.stationary().slip, fresh().slip);
  EXPECT_GT(sim.stationary().slip, slip_01);  // a steeper plane needs more slip for mu(s*) = tan(alpha)
  Command beyond;  // above alpha_c of PMMA: no sleeping state, with the reason
  beyond.inclination = 0.6;
  ASSERT_EQ(sim.submit(beyond), "");
  sim.advance_to(0.03);
  EXPECT_FALSE(sim.stationary().exists);
  EXPECT_EQ(sim.stationary().reason, fresh().reason);
  EXPECT_NE(sim.stationary().reason.find("slides downhill"), std::string::npos) << sim.stationary().reason;
  sim.reset();
  EXPECT_EQ(sim.model().plane.inclination, 0.1);
  EXPECT_TRUE(sim.stationary().exists);
  EXPECT_EQ(sim.stationary().phi, fresh().phi);
}

}  // namespace
