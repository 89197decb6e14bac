// The full model's right-hand side (dynamics.hpp) against closed forms and the energy balance.
#include <gtest/gtest.h>

#include <cmath>

#include "test_states.hpp"
#include "test_util.hpp"
#include "top_sim/dynamics.hpp"
#include "../../src/core/energy.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

using namespace top_sim;
using top_sim_test::upright_state;

namespace {

// dE/dt along the right-hand side by a central difference, against -dW_diss/dt.
void expect_power_balance(const Model& model, ContactMode mode, const StateVector& y, const char* what) {
  StateVector dydt;
  derivative(model, mode, y, dydt);
  const double h = 1e-7;
  StateVector a = y, b = y;
  for (std::size_t i = 0; i < idx::size; ++i) {
    a[i] += h * dydt[i];
    b[i] -= h * dydt[i];
  }
  const double dE = (mechanical_energy(model, a) - mechanical_energy(model, b)) / (2 * h);
  const double scale = energy_scale(model, y);
  EXPECT_NEAR(dE, -dydt[idx::w_diss], 1e-6 * scale) << what << ": dissipation " << dydt[idx::w_diss];
}

}  // namespace

// An upright top spinning at rest on a level plane: N = m g, no friction, no acceleration, no torque.
TEST(Dynamics, UprightSpinningTopAtRestCarriesItsWeightAndNothingElse) {
  const Model model = top_sim_test::scene_from(top_sim_test::standard_scene(0.0, 0.0)).model;
  Dynamics d;
  evaluate_dynamics(model, ContactMode::slipping, upright_state(200.0), d);
  const double mg = model.top.mass * model.plane.gravity;
  EXPECT_NEAR(d.normal_force, mg, 1e-12 * mg);
  EXPECT_LT(d.friction_force.norm(), 1e-12 * mg);
  EXPECT_LT(d.a_cm.norm(), 1e-12);
  EXPECT_LT(d.omega_dot.norm(), 1e-9);
  EXPECT_EQ(d.dissipation, 0.0);
}

// With model.normal_force: static the normal force is m g cos(alpha) whatever the motion (section 4).
TEST(Dynamics, StaticNormalForceIsMgCosAlphaInAnyState) {
  Scene scene = load_scene(top_sim_test::scene_path("default"));
  scene.model.normal_force = NormalForceModel::static_approximation;
  Simulator sim(load_scene(top_sim_test::scene_path("default")));
  sim.advance_to(0.37);  // nutating: the constrained N differs from m g cos(alpha) here
  Dynamics d;
  evaluate_dynamics(scene.model, ContactMode::slipping, sim.state(), d);
  const double expected = scene.model.top.mass * scene.model.plane.gravity * std::cos(scene.model.plane.inclination);
  EXPECT_NEAR(d.normal_force, expected, 1e-12 * expected);
}

// The state's kinematic rows: x' = u; in contact the gap and its rate stay 0; in flight the gap rate is the
// tip's normal velocity and its rate the normal part of gravity (nothing else acts).
TEST(Dynamics, KinematicRowsInContactAndInFlight) {
  const Model model = load_scene(top_sim_test::scene_path("default")).model;
  StateVector y = upright_state(100.0), dydt;
  y[idx::u] = 0.03;
  y[idx::u + 1] = -0.01;
  derivative(model, ContactMode::slipping, y, dydt);
  EXPECT_EQ(dydt[idx::x], 0.03);
  EXPECT_EQ(dydt[idx::x + 1], -0.01);
  EXPECT_EQ(dydt[idx::gap], 0.0);
  EXPECT_EQ(dydt[idx::gap_rate], 0.0);
  y[idx::gap] = 1e-3;
  y[idx::gap_rate] = 0.2;
  derivative(model, ContactMode::flight, y, dydt);
  EXPECT_EQ(dydt[idx::gap], 0.2);
  EXPECT_NEAR(dydt[idx::gap_rate], model.plane.g_plane.z(), 1e-12);
  EXPECT_NEAR(dydt[idx::u + 1], model.plane.g_plane.y(), 1e-12);  // downhill, free fall
  EXPECT_EQ(dydt[idx::w_diss], 0.0);
}

// dE/dt = -dW_diss/dt in each contact mode: slipping while nutating (default scene), rolling (coulomb), flight.
TEST(Dynamics, EnergyRateIsMinusTheDissipationInEveryMode) {
  Simulator sim(load_scene(top_sim_test::scene_path("default")));
  sim.advance_to(0.37);
  expect_power_balance(sim.model(), ContactMode::slipping, sim.state(), "slipping");
  Simulator rolling(load_scene(top_sim_test::scene_path("coulomb")));
  rolling.advance_to(1.0);
  ASSERT_EQ(rolling.contact_mode(), ContactMode::rolling);
  expect_power_balance(rolling.model(), ContactMode::rolling, rolling.state(), "rolling");
  StateVector y = sim.state();
  y[idx::gap] = 1e-3;
  expect_power_balance(sim.model(), ContactMode::flight, y, "flight");
}
