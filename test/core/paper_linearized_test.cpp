// Paper Fig. 5 analogue: the aluminium top on PMMA at alpha 0.1 with the linearized law, k = 1
// (config/scenes/fig5_linearized.yaml). r_cm(t), v_cm(t) and f f_hat(t) must end in physics.md
// section 5's sleeping state, computed here from the scene's parameters.
#include <gtest/gtest.h>

#include <cmath>

#include "../../src/output/run.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;

TEST(PaperFig5, LinearizedLawSleepsInTheAnalyticState) {
  const Scene scene = load_scene(TOP_SIM_TEST_CONFIG_DIR "/scenes/fig5_linearized.yaml");
  const Model& m = scene.model;
  ASSERT_EQ(m.friction.kind, FrictionLawKind::linearized);
  const double alpha = m.plane.inclination, g = m.plane.gravity;
  const double R = m.top.tip_radius, f = m.top.com_offset, spin = scene.initial.spin;
  // The law is expanded about the paper law's sleeping slip with mu0 = tan(alpha): s* = s0.
  ASSERT_NEAR(m.friction.mu0, std::tan(alpha), 1e-15);
  ASSERT_NEAR(m.friction.s0, 0.6 * (1.0 - std::sqrt(1.0 - std::tan(alpha) / 0.25)), 1e-15);
  ASSERT_DOUBLE_EQ(m.friction.k, 1.0);
  const double s_star = m.friction.s0;
  const double phi_star = 2.0 * std::atan(s_star);

  // physics.md section 5: f_hat* = -(R/f) n + f_g g_hat; v_h = R |w| |f_hat* x n| along h; v_d = v_h tan(phi*).
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ(), g_hat(0.0, -std::sin(alpha), -std::cos(alpha));
  const double f_g = -(R / f) * std::cos(alpha) - std::sqrt(1.0 - std::pow(R * std::sin(alpha) / f, 2));
  const Eigen::Vector3d f_star = -(R / f) * n + f_g * g_hat;
  Simulator sim(scene);
  RunOptions opt;
  opt.duration = scene.duration;
  const RunResult r = run(sim, opt);
  // The spin itself decays slowly (friction torque about the axis): v* is that of the final |omega|.
  const double w_end = r.final.angular_velocity.norm();
  EXPECT_GT(w_end, 0.5 * std::abs(spin));
  const double v_h = R * w_end * f_star.cross(n).norm();
  const Eigen::Vector3d v_star(v_h, -v_h * std::tan(phi_star), 0.0);
  ASSERT_EQ(r.final.fault, ContactFault::none) << r.final.fault_message;
  ASSERT_TRUE(r.phi_measured.has_value());
  // Tolerances: by 600 s the precession has decayed below 1e-7 rad (it shrinks about 4x per 50 s).
  EXPECT_NEAR(*r.phi_measured, phi_star, 1e-6);
  EXPECT_EQ(r.final.regime, Regime::sleeping);
  EXPECT_NEAR(r.final.slip, s_star, 1e-6);
  EXPECT_NEAR(r.final.mu, std::tan(alpha), 1e-6);
  EXPECT_NEAR(r.final.normal_force, m.top.mass * g * std::cos(alpha), 1e-6 * m.top.mass * g);
  EXPECT_LT((r.final.com_velocity - v_star).norm(), 1e-6 * v_star.norm());
  EXPECT_LT((r.final.figure_axis - f_star).norm(), 1e-6);
  // The centre of mass sits vertically (world) above the contact point: r_cm - r_t is parallel to -g.
  const Eigen::Vector3d lever = r.final.com - r.final.contact_point;
  EXPECT_LT(lever.normalized().cross(-g_hat).norm(), 1e-6);
  EXPECT_LT(r.max_energy_residual, 1e-9);
}

}  // namespace
