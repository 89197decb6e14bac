// The implicit midpoint method against closed forms: |R(iy)| = 1 and the frequency 2 atan(y/2)/h on an oscillator,
// second order and a bounded energy error on the frictionless top, the same bits sampled or not, and the named
// fault when Newton cannot converge.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "test_util.hpp"
#include "../../src/core/energy.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/plane.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;

// A harmonic oscillator of angular frequency w in (gap, gap_rate); every other rate is zero.
System oscillator(double w) {
  return [w](const StateVector& y, StateVector& d) {
    d.fill(0.0);
    d[idx::gap] = y[idx::gap_rate];
    d[idx::gap_rate] = -w * w * y[idx::gap];
  };
}

StateVector oscillator_start() {
  StateVector y{};
  y[idx::f + 2] = 1.0;  // a unit figure axis: the stepper renormalises it
  y[idx::gap] = 1.0;
  return y;
}

std::unique_ptr<Stepper> stepper(Method m, double dt, System system, const StateVector& y0) {
  IntegratorSettings s;
  s.method = m;
  s.dt = dt;
  std::unique_ptr<Stepper> st = make_stepper(s, std::move(system));
  st->reset(y0, 0.0);
  return st;
}

// sqrt(gap^2 + (gap_rate / w)^2): 1 for the exact solution from oscillator_start().
double amplitude(const StateVector& y, double w) { return std::hypot(y[idx::gap], y[idx::gap_rate] / w); }

Scene frictionless(Method m, double dt) { return top_sim_test::frictionless_scene(m, dt, 1e-12); }

// Largest component difference but the spin phase (unbounded, read by nothing) and W_diss (0 here).
double state_error(const StateVector& a, const StateVector& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < idx::size; ++i)
    if (i != idx::psi && i != idx::w_diss) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

}  // namespace

// R(iy) = (1 + iy/2) / (1 - iy/2): |R| = 1 and arg R = 2 atan(y/2). At h w = 2 (rk4: |R4(2i)| = 0.745 per step)
// the amplitude stays 1 to 1e-10 over 10^4 steps, and the phase after n steps is n 2 atan(1) = n pi/2 exactly.
TEST(ImplicitMidpoint, AnOscillatorKeepsItsAmplitudeAtAnyStepWithTheAnalyticFrequency) {
  const double w = 50.0, h = 2.0 / w;
  std::unique_ptr<Stepper> st = stepper(Method::implicit_midpoint, h, oscillator(w), oscillator_start());
  double worst = 0.0;
  for (int n = 1; n <= 10000; ++n) {
    st->step(std::numeric_limits<double>::infinity());
    worst = std::max(worst, std::abs(amplitude(st->state(), w) - 1.0));
  }
  note("midpoint h w = 2: largest amplitude error over 1e4 steps", worst);
  EXPECT_LT(worst, 1e-10);
  const double phase = 10000 * 2.0 * std::atan(0.5 * h * w);  // the numerical frequency 2 atan(h w / 2) / h
  EXPECT_NEAR(st->state()[idx::gap], std::cos(phase), 1e-9);
  EXPECT_NEAR(st->state()[idx::gap_rate] / w, -std::sin(phase), 1e-9);
  std::unique_ptr<Stepper> rk4 = stepper(Method::rk4, h, oscillator(w), oscillator_start());
  for (int n = 0; n < 20; ++n) rk4->step(std::numeric_limits<double>::infinity());
  EXPECT_NEAR(amplitude(rk4->state(), w), std::pow(std::hypot(1.0 / 3.0, 2.0 / 3.0), 20), 1e-9);  // |R4(2i)|^20
}

// Order 2: on the frictionless top over 0.2 s (about 10 nutation periods; h w = 0.33 to 0.08), halving dt divides
// the error against dopri5 at rtol 1e-12 by 4 within 10 %.
TEST(ImplicitMidpoint, IsSecondOrderOnTheFrictionlessTop) {
  const double t_end = 0.2;
  Simulator ref(frictionless(Method::dopri5, 1e-4));
  ASSERT_TRUE(ref.advance_to(t_end));
  double e[3];
  for (int k = 0; k < 3; ++k) {
    Simulator sim(frictionless(Method::implicit_midpoint, 1e-3 / (1 << k)));
    ASSERT_TRUE(sim.advance_to(t_end));
    ASSERT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
    e[k] = state_error(sim.state(), ref.state());
    note("midpoint frictionless error at dt = " + std::to_string(1e-3 / (1 << k)), e[k]);
  }
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(e[k] / e[k + 1], 4.0, 0.4) << e[k] << ", " << e[k + 1];
}

namespace {

// The largest relative energy error over 5 s, over its first and its last second; the largest | |f_hat| - 1 |.
struct EnergyRecord {
  double worst = 0.0, first_second = 0.0, last_second = 0.0, worst_unit = 0.0;
};

// The frictionless top on a level plane: no slide, a conservative rigid body on a frictionless point contact.
EnergyRecord energy_record(double dt) {
  Scene scene = frictionless(Method::implicit_midpoint, dt);
  scene.model.plane = make_plane(0.0, scene.model.plane.gravity);
  Simulator sim(scene);
  const double e0 = mechanical_energy(sim.model(), sim.state()), scale = energy_scale(sim.model(), sim.state());
  EnergyRecord r;
  const long n = std::lround(5.0 / dt), per_second = std::lround(1.0 / dt);
  for (long k = 1; k <= n; ++k) {
    EXPECT_TRUE(sim.advance_to(static_cast<double>(k) * dt));
    EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
    const double rel = std::abs(mechanical_energy(sim.model(), sim.state()) - e0) / scale;
    r.worst = std::max(r.worst, rel);
    if (k <= per_second) r.first_second = std::max(r.first_second, rel);
    if (k > n - per_second) r.last_second = std::max(r.last_second, rel);
    r.worst_unit = std::max(r.worst_unit, std::abs(figure_axis(sim.state()).norm() - 1.0));
  }
  return r;
}

}  // namespace

// Symplectic: on the level plane the energy error over 5 s at dt 5 ms stays below 1e-10 of the energy scale and does
// not drift (the last second's largest error is not above the first second's by more than 30 %); |f_hat| = 1 to
// rounding (midpoint keeps the quadratic invariant f . f). Measured: 5.0e-11 at 5 ms, 1.5e-10 at 10 ms, 2.4e-11 at
// 2.5 ms (where the Newton tolerance's share shows). On the inclined plane the error's envelope grows with the slide
// speed instead (m v_cm . dv of a bounded velocity error dv): 1.3e-7 at 5 s, 1.3e-6 at 50 s.
TEST(ImplicitMidpoint, TheLevelFrictionlessTopsEnergyErrorIsBoundedWithoutDrift) {
  const EnergyRecord r = energy_record(5e-3);
  note("midpoint dt 5 ms: largest relative energy error over 5 s", r.worst);
  note("midpoint dt 5 ms: over the first second", r.first_second);
  note("midpoint dt 5 ms: over the last second", r.last_second);
  EXPECT_LT(r.worst, 1e-10);
  EXPECT_LT(r.last_second, 1.3 * r.first_second);
  EXPECT_LT(r.worst_unit, 1e-14);
}

// Samples at every step end and at every 5th make the same steps and the same bits as one advance to 5 s.
TEST(ImplicitMidpoint, SampledAtStepEndsItMakesTheSameStepsAndBits) {
  const double dt = 5e-3, t_end = 5.0;
  Simulator whole(frictionless(Method::implicit_midpoint, dt));
  ASSERT_TRUE(whole.advance_to(t_end));
  for (int every : {1, 5}) {
    Simulator sampled(frictionless(Method::implicit_midpoint, dt));
    const long n = std::lround(t_end / (every * dt));
    for (long k = 1; k <= n; ++k) ASSERT_TRUE(sampled.advance_to(static_cast<double>(k) * every * dt));
    EXPECT_EQ(sampled.stats().steps, whole.stats().steps);
    EXPECT_EQ(sampled.stats().steps, 1000u);
    EXPECT_EQ(std::memcmp(sampled.state().data(), whole.state().data(), sizeof(StateVector)), 0)
        << "samples every " << every << " steps: " << state_error(sampled.state(), whole.state());
  }
}

// A rate with no solution of K = h f(y0 + K/2) (a sign flip larger than the step can cross) and a rate that turns
// NaN: the step throws naming the method, t and h, and leaves the state finite where it was.
TEST(ImplicitMidpoint, AStepThatCannotConvergeThrowsTheNamedFaultAndKeepsTheState) {
  const System sign_flip = [](const StateVector& y, StateVector& d) {
    d.fill(0.0);
    d[idx::gap] = y[idx::gap] > 0.0 ? -1e3 : 1e3;
  };
  const System nan_beyond = [](const StateVector& y, StateVector& d) {
    d.fill(0.0);
    d[idx::gap] = -1.0;
    if (y[idx::gap] < 0.5) d[idx::gap] = std::numeric_limits<double>::quiet_NaN();
  };
  for (const System& system : {sign_flip, nan_beyond}) {
    StateVector y0 = oscillator_start();
    y0[idx::gap] = 0.51;
    std::unique_ptr<Stepper> st = stepper(Method::implicit_midpoint, 0.1, system, y0);
    try {
      st->step(std::numeric_limits<double>::infinity());
      FAIL() << "no fault";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      std::cout << "[ measured ] " << what << "\n";
      EXPECT_NE(what.find("implicit_midpoint"), std::string::npos) << what;
      EXPECT_NE(what.find("t = 0 s"), std::string::npos) << what;
      EXPECT_NE(what.find("h = 0.10000000000000001 s"), std::string::npos) << what;
    }
    EXPECT_TRUE(all_finite(st->state()));
    EXPECT_EQ(st->state()[idx::gap], 0.51);
    EXPECT_EQ(st->time(), 0.0);
  }
}

// Through the Simulator: an absurd dt (0.2 s) on the default scene, whose regularised friction is stiff, ends in the
// numerical fault naming the method and the step; the state stays the finite initial one.
TEST(ImplicitMidpoint, TheSimulatorReportsANewtonFailureAsANumericalFault) {
  Scene scene = load_scene(top_sim_test::scene_path("default"));
  scene.integrator.method = Method::implicit_midpoint;
  scene.integrator.dt = 0.2;
  Simulator sim(scene);
  const StateVector y0 = sim.state();
  sim.advance_to(1.0);
  EXPECT_EQ(sim.fault(), ContactFault::numerical);
  EXPECT_NE(sim.fault_message().find("implicit_midpoint: the Newton iteration failed at t = 0 s with h = 0.2"),
            std::string::npos)
      << sim.fault_message();
  EXPECT_TRUE(all_finite(sim.state()));
  EXPECT_EQ(sim.time(), 0.0);
  EXPECT_EQ(std::memcmp(sim.state().data(), y0.data(), sizeof(StateVector)), 0);
}
