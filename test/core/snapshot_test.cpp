// The Snapshot (snapshot.hpp): its fields are the state's geometry and energy, and all_finite catches every field.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "test_util.hpp"
#include "../../src/core/energy.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/snapshot.hpp"

using namespace top_sim;

// At a nutating instant of the default scene: positions, velocities, spin and energy from the state itself.
TEST(Snapshot, FieldsAreTheStatesGeometryAndEnergy) {
  Simulator sim(load_scene(top_sim_test::scene_path("default")));
  sim.advance_to(0.37);
  const Snapshot s = sim.snapshot();
  const StateVector& y = sim.state();
  const Model& m = sim.model();
  const double R = m.top.tip_radius, f = m.top.com_offset;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized(), w = angular_velocity(y);
  const Eigen::Vector3d tip(y[idx::x], y[idx::x + 1], R + y[idx::gap]);
  const double tol = 1e-12;
  EXPECT_NEAR(s.t, sim.time(), 0.0);
  EXPECT_NEAR(s.alpha, m.plane.inclination, 0.0);
  EXPECT_LT((s.tip_center - tip).norm(), tol);
  EXPECT_LT((s.com - (tip + f * f_hat)).norm(), tol);
  EXPECT_LT((s.contact_point - (tip - Eigen::Vector3d(0, 0, R))).norm(), tol);
  EXPECT_LT((s.figure_axis - f_hat).norm(), tol);
  EXPECT_LT((s.angular_velocity - w).norm(), tol);
  EXPECT_NEAR(s.spin, w.dot(f_hat), tol * std::abs(s.spin));
  EXPECT_LT((s.com_velocity - (velocity3(y) + f * w.cross(f_hat))).norm(), tol);
  EXPECT_LT((s.orientation * Eigen::Vector3d::UnitZ() - f_hat).norm(), 1e-12);  // the body z axis is the figure axis
  EXPECT_NEAR(s.energy, mechanical_energy(m, y), tol * std::abs(s.energy));
  EXPECT_EQ(s.dissipated_work, y[idx::w_diss]);
  EXPECT_TRUE(all_finite(s));
}

// Every number all_finite guards: one NaN in any of them, and the snapshot is not finite.
TEST(Snapshot, AllFiniteCatchesANaNInEveryField) {
  const Snapshot clean;
  EXPECT_TRUE(all_finite(clean));
  const double nan = std::nan("");
  const std::vector<std::function<void(Snapshot&)>> poison = {
      [&](Snapshot& s) { s.t = nan; },
      [&](Snapshot& s) { s.alpha = nan; },
      [&](Snapshot& s) { s.spin = nan; },
      [&](Snapshot& s) { s.rotor_spin = nan; },
      [&](Snapshot& s) { s.spin_phase = nan; },
      [&](Snapshot& s) { s.slip = nan; },
      [&](Snapshot& s) { s.mu = nan; },
      [&](Snapshot& s) { s.normal_force = nan; },
      [&](Snapshot& s) { s.phi = nan; },
      [&](Snapshot& s) { s.phi_star = nan; },
      [&](Snapshot& s) { s.gap = nan; },
      [&](Snapshot& s) { s.energy = nan; },
      [&](Snapshot& s) { s.dissipated_work = nan; },
      [&](Snapshot& s) { s.energy_balance_residual = nan; },
      [&](Snapshot& s) { s.drilling_torque = nan; },
      [&](Snapshot& s) { s.patch_radius = nan; },
      [&](Snapshot& s) { s.tip_center.y() = nan; },
      [&](Snapshot& s) { s.com.z() = nan; },
      [&](Snapshot& s) { s.com_velocity.x() = nan; },
      [&](Snapshot& s) { s.tip_velocity.y() = nan; },
      [&](Snapshot& s) { s.contact_point.x() = nan; },
      [&](Snapshot& s) { s.figure_axis.z() = nan; },
      [&](Snapshot& s) { s.angular_velocity.x() = nan; },
      [&](Snapshot& s) { s.friction_force.y() = nan; },
      [&](Snapshot& s) { s.com_acceleration.z() = nan; },
      [&](Snapshot& s) { s.orientation.w() = nan; },
  };
  for (std::size_t i = 0; i < poison.size(); ++i) {
    Snapshot s = clean;
    poison[i](s);
    EXPECT_FALSE(all_finite(s)) << "field " << i;
  }
}
