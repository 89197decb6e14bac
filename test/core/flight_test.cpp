// Flight in closed form (physics.md section 9, "Flight in closed form"): against a tight dopri5 integration of the
// flight right-hand side, its conserved quantities, and the touchdown time against a parabola and a stepped search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "test_util.hpp"
#include "top_sim/dynamics.hpp"
#include "../../src/core/energy.hpp"
#include "../../src/core/flight.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;

// A tilted gyrostat on a 0.2 rad incline: I_f 5e-6, I_d 3e-6, rotor J 1.5e-6, bearing c (0: uncoupled).
// kCoupled's bearing decay rate c I_f / (J I_f') is 66.7 1/s: nu falls by e^-5.2 over five precession periods.
constexpr double kCoupled = 7.0e-5;

Model gyrostat(double coupling = 0.0) {
  Model m;
  m.top.has_rotor = true;
  m.top.rotor.inertia_axial = 1.5e-6;
  m.top.rotor.coupling = coupling;
  m.plane = make_plane(0.2, 9.81);
  return m;
}

// In flight 2 mm above the plane, rising, tilted 0.4 rad, shell spin 150 rad/s with a transverse 40 rad/s, rotor
// 300 rad/s relative: the precession rate |L| / I_d is about 180 rad/s, well apart from the spin.
StateVector flying_state() {
  StateVector y{};
  const Eigen::Vector3d f_hat(std::sin(0.4), 0.0, std::cos(0.4));
  const Eigen::Vector3d transverse = f_hat.cross(Eigen::Vector3d::UnitY()).normalized();
  set_position(y, Eigen::Vector2d(0.01, -0.02));
  set_velocity3(y, Eigen::Vector3d(0.3, -0.1, 0.4));
  set_figure_axis(y, f_hat);
  set_angular_velocity(y, 150.0 * f_hat + 40.0 * transverse);
  y[idx::nu] = 300.0;
  y[idx::gap] = 2e-3;
  y[idx::psi] = 0.7;
  return y;
}

// L about the centre of mass (physics.md section 6).
Eigen::Vector3d angular_momentum(const Model& model, const StateVector& y) {
  const Top& top = model.top;
  const Eigen::Vector3d f = figure_axis(y).normalized(), w = angular_velocity(y);
  const double w_f = w.dot(f), J = top.rotor.inertia_axial;
  return top.inertia_transverse * w + ((shell_axial_inertia(top) - top.inertia_transverse) * w_f + J * (w_f + y[idx::nu])) * f;
}

Eigen::Vector3d com_velocity(const Model& model, const StateVector& y) {
  return velocity3(y) + angular_velocity(y).cross(model.top.com_offset * figure_axis(y).normalized());
}

std::unique_ptr<Stepper> reference_stepper(const Model& model, const StateVector& y0) {
  IntegratorSettings s;
  s.method = Method::dopri5;
  s.rtol = 1e-12;
  s.atol = 1e-14;
  s.dt = 1e-6;
  auto st = make_stepper(s, [&model](const StateVector& y, StateVector& dydt) {
    derivative(model, ContactMode::flight, y, dydt);
  });
  st->reset(y0, 0.0);
  return st;
}

}  // namespace

// Over five precession periods the closed form and dopri5 (rtol 1e-12, atol 1e-14) agree to the reference's own
// accumulated error: 1e-11 relative in the angular quantities, 1e-13 m in the positions, 1e-11 m/s in u; with a
// bearing also nu (1e-11 of nu0) and the dissipated work (1e-11 of the rotor's initial relative kinetic energy).
void expect_closed_form_follows_dopri5(double coupling) {
  SCOPED_TRACE("rotor coupling " + std::to_string(coupling));
  const Model model = gyrostat(coupling);
  const StateVector y0 = flying_state();
  const FlightMotion motion = flight_motion(model, y0, 0.0);
  EXPECT_GT(motion.rate, 100.0);
  const double t_end = 5.0 * 2.0 * M_PI / motion.rate;
  auto st = reference_stepper(model, y0);
  double worst_f = 0.0, worst_w = 0.0, worst_psi = 0.0, worst_x = 0.0, worst_u = 0.0, worst_nu = 0.0, worst_W = 0.0;
  const double nu0 = y0[idx::nu], rotor_energy = 0.5 * model.top.rotor.inertia_axial * nu0 * nu0;
  for (int k = 1; k <= 50; ++k) {
    const double t = t_end * k / 50.0;
    while (st->time() < t) st->step(t_end);
    StateVector ref, y;
    st->state_at(t, ref);
    flight_state(model, motion, t, y);
    worst_f = std::max(worst_f, (figure_axis(y) - figure_axis(ref)).norm());
    worst_w = std::max(worst_w, (angular_velocity(y) - angular_velocity(ref)).norm() / angular_velocity(ref).norm());
    worst_psi = std::max(worst_psi, std::abs(y[idx::psi] - ref[idx::psi]) / std::abs(ref[idx::psi]));
    const Eigen::Vector3d dx(y[idx::x] - ref[idx::x], y[idx::x + 1] - ref[idx::x + 1], y[idx::gap] - ref[idx::gap]);
    worst_x = std::max(worst_x, dx.norm());
    worst_u = std::max(worst_u, (velocity3(y) - velocity3(ref)).norm());
    worst_nu = std::max(worst_nu, std::abs(y[idx::nu] - ref[idx::nu]) / nu0);
    worst_W = std::max(worst_W, std::abs(y[idx::w_diss] - ref[idx::w_diss]) / rotor_energy);
    if (coupling == 0.0) {
      EXPECT_EQ(y[idx::nu], y0[idx::nu]);  // no bearing torque: the relative rotor spin stays
    }
  }
  if (coupling > 0.0) {  // the bearing has done its work: nu0 e^-5.2 left
    StateVector y;
    flight_state(model, motion, t_end, y);
    EXPECT_NEAR(y[idx::nu], nu0 * std::exp(-motion.decay * t_end), 1e-12 * nu0);
    EXPECT_LT(y[idx::nu], 0.01 * nu0);
  }
  EXPECT_LT(worst_nu, 1e-11);
  EXPECT_LT(worst_W, 1e-11);
  EXPECT_LT(worst_f, 1e-11);
  EXPECT_LT(worst_w, 1e-11);
  EXPECT_LT(worst_psi, 1e-11);
  EXPECT_LT(worst_x, 1e-13);
  EXPECT_LT(worst_u, 1e-11);
  note("closed form vs dopri5 rtol 1e-12, 5 precession periods: max |df_hat|", worst_f);
  note("closed form vs dopri5: max |d omega| / |omega|", worst_w);
  note("closed form vs dopri5: max |d position| [m]", worst_x);
  note("closed form vs dopri5: max |d u| [m/s]", worst_u);
  note("closed form vs dopri5: max |d psi| / |psi|", worst_psi);
  note("closed form vs dopri5: max |d nu| / nu0", worst_nu);
  note("closed form vs dopri5: max |d W_diss| / (J nu0^2 / 2)", worst_W);
}

TEST(ClosedFormFlight, FollowsATightDopri5IntegrationOfTheFlightRightHandSide) { expect_closed_form_follows_dopri5(0.0); }

TEST(ClosedFormFlight, WithARotorBearingFollowsATightDopri5Integration) {
  EXPECT_TRUE(flight_in_closed_form(gyrostat(kCoupled)));
  expect_closed_form_follows_dopri5(kCoupled);
}

// Energy plus the bearing's dissipated work, L about the centre of mass and the momentum less the impulse of gravity
// hold to rounding (1e-13 relative) over a hundred precession periods, without and with a bearing.
void expect_conserved(double coupling) {
  SCOPED_TRACE("rotor coupling " + std::to_string(coupling));
  const Model model = gyrostat(coupling);
  const StateVector y0 = flying_state();
  const FlightMotion motion = flight_motion(model, y0, 0.0);
  const double E0 = mechanical_energy(model, y0), scale = energy_scale(model, y0);
  const Eigen::Vector3d L0 = angular_momentum(model, y0), p0 = model.top.mass * com_velocity(model, y0);
  const double t_end = 100.0 * 2.0 * M_PI / motion.rate;
  for (int k = 1; k <= 1000; ++k) {
    const double t = t_end * k / 1000.0;
    StateVector y;
    flight_state(model, motion, t, y);
    EXPECT_NEAR(mechanical_energy(model, y) + y[idx::w_diss], E0, 1e-13 * scale) << "t = " << t;
    EXPECT_LT((angular_momentum(model, y) - L0).norm(), 1e-13 * L0.norm()) << "t = " << t;
    const Eigen::Vector3d p = model.top.mass * (com_velocity(model, y) - t * model.plane.g_plane);
    EXPECT_LT((p - p0).norm(), 1e-13 * p0.norm()) << "t = " << t;
    EXPECT_NEAR(figure_axis(y).norm(), 1.0, 1e-15);
  }
}

TEST(ClosedFormFlight, ConservesEnergyAngularMomentumAndMomentum) {
  expect_conserved(0.0);
  expect_conserved(kCoupled);
}

// Without spin or tilt the gap is a parabola: touchdown at (v + sqrt(v^2 + 2 g h)) / g, g = g cos(alpha), to the
// bisection's stop (1e-15 s below t = 1 s) and rounding: 2e-15 s.
TEST(ClosedFormFlight, TouchdownOfAnUprightTopWithoutSpinIsTheParabolasRoot) {
  const Model model = gyrostat();
  StateVector y{};
  set_figure_axis(y, Eigen::Vector3d::UnitZ());
  set_velocity3(y, Eigen::Vector3d(0.2, 0.0, 0.35));
  y[idx::gap] = 1e-3;
  const double g = -model.plane.g_plane.z(), v = 0.35, h = 1e-3;
  const double expected = (v + std::sqrt(v * v + 2.0 * g * h)) / g;
  const double t = touchdown_time(model, flight_motion(model, y, 0.0));
  EXPECT_NEAR(t, expected, 2e-15);
}

// A spinning, precessing bounce (gap 0, rising, a flight of several precession periods): touchdown against dopri5
// (rtol 1e-12) and a bisection of its dense output, to the reference's height error 1e-12 m over the closing speed
// (~0.3 m/s): 1e-11 s.
TEST(ClosedFormFlight, TouchdownOfAPrecessingTopMatchesASteppedSearch) {
  const Model model = gyrostat();
  StateVector y0 = flying_state();
  y0[idx::gap] = 0.0;
  y0[idx::gap_rate] = 0.3;
  const double t_touch = touchdown_time(model, flight_motion(model, y0, 0.0));
  ASSERT_TRUE(std::isfinite(t_touch));
  auto st = reference_stepper(model, y0);
  auto closing = [](const StateVector& y) { return y[idx::gap] <= 0.0 && y[idx::gap_rate] < 0.0; };
  while (!closing(st->state())) st->step(1.0);
  // The first closing instant inside the last step, on a fine grid then bisected.
  double lo = st->previous_time(), hi = st->time();
  StateVector y;
  for (int k = 1; k <= 1000; ++k) {
    const double t = lo + (st->time() - st->previous_time()) * k / 1000.0;
    st->state_at(t, y);
    if (closing(y)) { hi = t; break; }
  }
  lo = std::max(st->previous_time(), hi - (st->time() - st->previous_time()) / 1000.0);
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    st->state_at(mid, y);
    (closing(y) ? hi : lo) = mid;
  }
  EXPECT_NEAR(t_touch, hi, 1e-11);
  note("touchdown: closed form - dopri5 reference [s]", t_touch - hi);
  EXPECT_GT(t_touch, 2.0 * 2.0 * M_PI / flight_motion(model, y0, 0.0).rate);  // a flight over several precessions
}

// Through the Simulator: a ball dropped from h0 touches down at sqrt(2 h0 / g) with dopri5, to the bisection's stop
// and rounding (2e-15 s); a sample half way is the parabola to rounding.
TEST(ClosedFormFlight, SimulatorTouchdownOfADroppedBallIsExact) {
  const std::string yaml =
      "top: {mass: 0.1, tip_radius: 0.01, com_offset: 0.0, inertia_axial: 4.0e-6, inertia_transverse: 4.0e-6}\n"
      "plane: {inclination: 0.0, gravity: 9.81}\nfriction: {law: coulomb, mu: 0.0}\n"
      "initial: {tilt: 0.0, spin: 0.0, gap: 0.02}\n";
  Simulator sim(top_sim_test::scene_from(yaml));
  const double t_drop = std::sqrt(2.0 * 0.02 / 9.81);
  sim.advance_to(0.5 * t_drop);  // a sample inside the flight is the closed form
  EXPECT_NEAR(sim.snapshot().gap, 0.02 - 0.5 * 9.81 * 0.25 * t_drop * t_drop, 1e-16);
  sim.advance_to(1.1 * t_drop);
  const std::vector<ModeSwitch> sw = sim.take_mode_switches();
  ASSERT_FALSE(sw.empty());
  EXPECT_EQ(sw[0].kind, ModeSwitchKind::touchdown);
  EXPECT_NEAR(sw[0].t, t_drop, 2e-15);
}
