// The mechanical energy and its balance (physics.md section 4) against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "test_states.hpp"
#include "test_util.hpp"
#include "../../src/core/energy.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"

using namespace top_sim;
using top_sim_test::upright_state;

// Level plane, upright, spinning, at rest: E = I_f W^2 / 2 + m g (R + f).
TEST(Energy, UprightSpinningTopIsItsSpinAndItsHeight) {
  const Model model = top_sim_test::scene_from(top_sim_test::standard_scene(0.0, 0.0)).model;
  const Top& t = model.top;
  const double w = 150.0;
  const double expected = 0.5 * t.inertia_axial * w * w + t.mass * model.plane.gravity * (t.tip_radius + t.com_offset);
  EXPECT_NEAR(mechanical_energy(model, upright_state(w)), expected, 1e-14 * expected);
}

// On the incline, a step uphill (+y in the plane frame) raises the energy by m g sin(alpha) per metre.
TEST(Energy, AStepUphillCostsMgSinAlphaPerMetre) {
  const double alpha = 0.2, step = 0.37;
  const Model model = top_sim_test::scene_from(top_sim_test::standard_scene(alpha, 100.0)).model;
  StateVector y = upright_state(100.0), up = y;
  up[idx::x + 1] += step;
  const double rise = mechanical_energy(model, up) - mechanical_energy(model, y);
  EXPECT_NEAR(rise, model.top.mass * model.plane.gravity * std::sin(alpha) * step, 1e-12);
}

// A tilted, nutating, sliding top: E = m |v_cm|^2 / 2 + omega . I omega / 2 + m g z_cm, written out independently
// (v_cm = u + f omega x f_hat; I = I_d 1 + (I_f - I_d) f_hat f_hat^T; z_cm from the plane's tilt).
TEST(Energy, TiltedSlidingNutatingTopMatchesTheRigidBodyFormula) {
  const double alpha = 0.1;
  const Model model = top_sim_test::scene_from(top_sim_test::standard_scene(alpha, 0.0)).model;
  const Top& t = model.top;
  StateVector y{};
  const Eigen::Vector3d f_hat = Eigen::Vector3d(0.3, -0.2, 0.9).normalized();
  const Eigen::Vector3d w(4.0, -7.0, 120.0), u(0.05, -0.02, 0.0);
  for (int i = 0; i < 3; ++i) {
    y[idx::f + i] = f_hat[i];
    y[idx::omega + i] = w[i];
  }
  y[idx::u] = u.x();
  y[idx::u + 1] = u.y();
  y[idx::x] = 0.4;
  y[idx::x + 1] = -0.25;
  const Eigen::Vector3d v_cm = u + t.com_offset * w.cross(f_hat);
  const Eigen::Vector3d Iw = t.inertia_transverse * w + (t.inertia_axial - t.inertia_transverse) * w.dot(f_hat) * f_hat;
  // World height of the centre of mass: the plane-frame point's components along the world vertical.
  const Eigen::Vector3d r_cm(y[idx::x], y[idx::x + 1], t.tip_radius);
  const Eigen::Vector3d r = r_cm + t.com_offset * f_hat;
  const double z_world = r.y() * std::sin(alpha) + r.z() * std::cos(alpha);
  const double expected = 0.5 * t.mass * v_cm.squaredNorm() + 0.5 * w.dot(Iw) + t.mass * model.plane.gravity * z_world;
  EXPECT_NEAR(mechanical_energy(model, y), expected, 1e-13 * std::abs(expected));
}

// The residual's scale: kinetic energy plus m g (R + |f|), |f| also for a tippe top's negative offset.
TEST(Energy, ScaleIsKineticEnergyPlusTheLiftOfTheCentreOfMass) {
  for (const char* scene : {"default", "tippe_top"}) {
    const Model model = load_scene(top_sim_test::scene_path(scene)).model;
    const Top& t = model.top;
    const double w = 80.0;
    const double expected =
        0.5 * t.inertia_axial * w * w + t.mass * model.plane.gravity * (t.tip_radius + std::abs(t.com_offset));
    EXPECT_NEAR(energy_scale(model, upright_state(w)), expected, 1e-14 * expected) << scene;
  }
}

// The balance: 0 after a rebase, 0 while energy moves into W_diss, and a gain of dE shows as dE / scale.
TEST(EnergyBalance, ResidualIsTheRelativeGainOfEPlusWdiss) {
  const Model model = top_sim_test::scene_from(top_sim_test::standard_scene(0.1, 200.0)).model;
  StateVector y = upright_state(200.0);
  EnergyBalance balance;
  balance.rebase(model, y);
  const double E = mechanical_energy(model, y);
  EXPECT_EQ(balance.residual(E, y), 0.0);
  y[idx::w_diss] = 0.01;
  EXPECT_NEAR(balance.residual(E - 0.01, y), 0.0, 1e-15);
  EXPECT_NEAR(balance.residual(E, y), 0.01 / balance.scale, 1e-15);
}
