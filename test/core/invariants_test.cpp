// Conserved quantities (physics.md section 4): the energy balance E + W_diss of the constrained model, and what a
// frictionless plane conserves. Every conserved quantity is recomputed here from the state, not taken from the core.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "test_util.hpp"
#include "../../src/core/energy.hpp"

namespace {

using namespace top_sim;
using top_sim_test::scene_from;

// E = 1/2 m |v_cm|^2 + 1/2 omega . I omega + m g z_cm,W with z_W = sin(alpha) y_P + cos(alpha) z_P (R_WP = Rot_x(alpha)).
double energy_by_hand(const Model& m, const Snapshot& s) {
  const Top& t = m.top;
  const Eigen::Vector3d f = s.figure_axis, w = s.angular_velocity;
  const double w_f = w.dot(f);
  const double rot = t.inertia_transverse * (w.squaredNorm() - w_f * w_f) + t.inertia_axial * w_f * w_f;
  const double a = s.alpha;
  const double z_world = std::sin(a) * s.com.y() + std::cos(a) * s.com.z();
  return 0.5 * t.mass * s.com_velocity.squaredNorm() + 0.5 * rot + t.mass * m.plane.gravity * z_world;
}

// Angular momentum about the centre of mass, plain top: L = I_d omega + (I_f - I_d)(omega . f_hat) f_hat.
Eigen::Vector3d angular_momentum(const Model& m, const Snapshot& s) {
  const Top& t = m.top;
  const Eigen::Vector3d f = s.figure_axis, w = s.angular_velocity;
  return t.inertia_transverse * w + (t.inertia_axial - t.inertia_transverse) * w.dot(f) * f;
}

// Constrained model, with friction: E + W_diss constant to 1e-8 relative over 5 s at rtol 1e-10 (issue item 7).
TEST(EnergyBalance, ConstrainedModelKeepsEPlusWdissTo1e8) {
  Scene scene = load_scene(top_sim_test::scene_path("default"));
  scene.integrator.rtol = 1e-10;
  scene.integrator.atol = 1e-12;
  Simulator sim(scene);
  const Snapshot s0 = sim.snapshot();
  const double scale = energy_scale(scene.model, sim.state());
  double worst = 0.0;
  Snapshot s;
  for (int k = 1; k <= 500; ++k) {
    sim.advance_to(0.01 * k);
    s = sim.snapshot();
    ASSERT_EQ(top_sim_test::nonfinite_fields(s), "") << "t = " << s.t;
    worst = std::max(worst, std::abs(energy_by_hand(scene.model, s) + s.dissipated_work - energy_by_hand(scene.model, s0)) / scale);
  }
  ASSERT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  // The balance is meaningful only if friction did real work: W_diss must dwarf the tolerance.
  EXPECT_GT(s.dissipated_work / scale, 1e-5);
  // The energy computed here and the core's own agree (same definition, rounding only).
  EXPECT_NEAR(s.energy, energy_by_hand(scene.model, s), 1e-12 * scale);
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(sim.max_energy_residual(), 1e-8);
  top_sim_test::note("max |E + W_diss - E0| / scale over 5 s at rtol 1e-10", worst);
  top_sim_test::note("W_diss(5 s) / scale", s.dissipated_work / scale);
}

// Frictionless plane (Coulomb mu = 0): the contact force is N n only. Proofs of what is conserved:
//  - Energy: W_diss' = mu N t.v_t = 0 and N does no work (n . v_t = 0), so E is constant.
//  - Linear momentum: m a_cm = m g + N n. In the plane frame g = -g (0, sin a, cos a), so the in-plane
//    component along h = e_x has no force at all: m v_cm,x is constant; at alpha = 0 also m v_cm,y.
//  - Angular momentum about the centre of mass: dL/dt = rho x N n with rho = -(R n + f f_hat), i.e.
//    dL/dt = -N f (f_hat x n), which is perpendicular to n and to f_hat. n is fixed (the plane is at rest), so
//    L . n is constant. For L . f_hat: d(L.f_hat)/dt = torque . f_hat + L . (omega x f_hat); the torque term
//    is 0 and L . (omega x f_hat) = I_d omega . (omega x f_hat) + (...) f_hat . (omega x f_hat) = 0, so
//    L . f_hat = I_f omega . f_hat is constant (the spin does not change).
struct Conserved {
  double energy, p_x, p_y, L_n, L_f;
};

Conserved conserved(const Model& m, const Snapshot& s) {
  const Eigen::Vector3d L = angular_momentum(m, s);
  return {energy_by_hand(m, s), m.top.mass * s.com_velocity.x(), m.top.mass * s.com_velocity.y(), L.z(),
          L.dot(s.figure_axis)};
}

void check_frictionless(double alpha) {
  SCOPED_TRACE("alpha = " + std::to_string(alpha));
  // A strongly nutating start (tilt 0.3, transverse angular velocity, initial velocity) so nothing is trivially 0.
  Scene scene = scene_from(
      "top: aluminium\n"
      "plane: {inclination: " + top_sim_test::num(alpha) + "}\n"
      "friction: {law: coulomb, mu: 0.0}\n"
      "initial: {tilt: 0.3, tilt_azimuth: 0.7, spin: 200.0, angular_velocity_transverse: [4.0, -3.0],"
      " velocity: [0.05, 0.02]}\n"
      "integrator: {method: dopri5, rtol: 1.0e-10, atol: 1.0e-12}\n");
  Simulator sim(scene);
  const Model& m = scene.model;
  const Snapshot s0 = sim.snapshot();
  const Conserved c0 = conserved(m, s0);
  // Scales: energy as the core's energy_scale; momentum m sqrt(g f) (the nutation speed scale) plus the initial
  // momentum; angular momentum |L(0)|.
  const double e_scale = energy_scale(m, sim.state());
  const double p_scale = m.top.mass * (std::sqrt(m.plane.gravity * m.top.com_offset) + s0.com_velocity.norm());
  const double l_scale = angular_momentum(m, s0).norm();
  double d_e = 0, d_px = 0, d_py = 0, d_ln = 0, d_lf = 0, swing_ln = 0, swing_vy = 0;
  for (int k = 1; k <= 500; ++k) {
    sim.advance_to(0.01 * k);
    const Snapshot s = sim.snapshot();
    ASSERT_EQ(top_sim_test::nonfinite_fields(s), "") << "t = " << s.t;
    const Conserved c = conserved(m, s);
    d_e = std::max(d_e, std::abs(c.energy - c0.energy) / e_scale);
    d_px = std::max(d_px, std::abs(c.p_x - c0.p_x) / p_scale);
    d_py = std::max(d_py, std::abs(c.p_y - c0.p_y) / p_scale);
    d_ln = std::max(d_ln, std::abs(c.L_n - c0.L_n) / l_scale);
    d_lf = std::max(d_lf, std::abs(c.L_f - c0.L_f) / l_scale);
    // Control quantities that are NOT conserved, to show the run is not trivial: L_x (the torque has an x part).
    swing_ln = std::max(swing_ln, std::abs(angular_momentum(m, s).x() - angular_momentum(m, s0).x()) / l_scale);
    swing_vy = std::max(swing_vy, std::abs(c.p_y - c0.p_y) / p_scale);
  }
  ASSERT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_EQ(sim.snapshot().dissipated_work, 0.0);  // mu = 0: nothing is dissipated, exactly
  // rtol 1e-10 over 5 s: 1e-8 relative leaves two decades for the accumulated integration error.
  EXPECT_LT(d_e, 1e-8);
  EXPECT_LT(d_px, 1e-8);
  EXPECT_LT(d_ln, 1e-8);
  EXPECT_LT(d_lf, 1e-8);
  EXPECT_GT(swing_ln, 1e-3) << "L_x should change: the run would not test anything";
  if (alpha == 0.0) {
    EXPECT_LT(d_py, 1e-8);
  } else {
    // Downhill gravity changes p_y by m g sin(alpha) t: 5 s at 0.1 rad is ~5 m/s, far above the scale.
    EXPECT_GT(swing_vy, 1.0);
  }
  top_sim_test::note("frictionless alpha " + std::to_string(alpha) + ": max rel drift E", d_e);
  top_sim_test::note("frictionless alpha " + std::to_string(alpha) + ": max rel drift p_x", d_px);
  top_sim_test::note("frictionless alpha " + std::to_string(alpha) + ": max rel drift L.n", d_ln);
  top_sim_test::note("frictionless alpha " + std::to_string(alpha) + ": max rel drift L.f_hat", d_lf);
}

TEST(Frictionless, ConservesEnergyInPlaneMomentumAlongHAndAngularMomentumAlongNAndFhat) { check_frictionless(0.1); }

TEST(Frictionless, OnAHorizontalPlaneBothInPlaneMomentumComponentsAreConserved) { check_frictionless(0.0); }

}  // namespace
