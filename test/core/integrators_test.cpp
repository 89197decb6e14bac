// The time steppers of integrators.hpp against closed-form solutions: observed convergence orders, dense output,
// event location on the dense output, restart after reset(), the stiff-layer hand-over and right-hand-side counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "test_util.hpp"
#include "top_sim/integrators.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;

const double kPi = std::acos(-1.0);

// ---- the test problem --------------------------------------------------------------------------------------------

// Every component has a closed form (exact() below). The rates read no x, w_diss or psi (rosenbrock4's Jacobian
// assumes nothing depends on them), and (gap, gap_rate) is the position/velocity pair of a harmonic oscillator.
void rates(const StateVector& y, StateVector& d) {
  d[idx::x] = y[idx::u];  // positions driven by the velocities
  d[idx::x + 1] = y[idx::u + 1];
  d[idx::u] = -y[idx::u + 1];  // a velocity turning at 1 rad/s
  d[idx::u + 1] = y[idx::u];
  d[idx::f] = -y[idx::f + 1];  // the unit figure axis turning about z at 1 rad/s
  d[idx::f + 1] = y[idx::f];
  d[idx::f + 2] = 0.0;
  d[idx::omega] = -y[idx::omega];  // decay
  d[idx::omega + 1] = 0.5;         // linear growth
  d[idx::omega + 2] = -2.0 * y[idx::omega + 2];
  d[idx::nu] = y[idx::omega];
  d[idx::w_diss] = y[idx::omega] * y[idx::omega];
  d[idx::gap] = y[idx::gap_rate];  // gap'' = -gap
  d[idx::gap_rate] = -y[idx::gap];
  d[idx::psi] = 1.0 + y[idx::u];
}

// The solution of rates() from exact(0).
StateVector exact(double t) {
  const double c = std::cos(t), s = std::sin(t), e = std::exp(-t);
  StateVector y{};
  y[idx::x] = s;
  y[idx::x + 1] = 1.0 - c;
  y[idx::u] = c;
  y[idx::u + 1] = s;
  y[idx::f] = c;
  y[idx::f + 1] = s;
  y[idx::f + 2] = 0.0;
  y[idx::omega] = e;
  y[idx::omega + 1] = 0.5 * t;
  y[idx::omega + 2] = e * e;
  y[idx::nu] = 1.0 - e;
  y[idx::w_diss] = 0.5 * (1.0 - e * e);
  y[idx::gap] = c;
  y[idx::gap_rate] = -s;
  y[idx::psi] = t + s;
  return y;
}

// Largest |y''| of exact() over t >= 0 (e^-2t in omega_z): bounds the error of linear interpolation.
constexpr double kMaxSecondDerivative = 4.0;

double max_error(const StateVector& y, const StateVector& ref) {
  double e = 0.0;
  for (std::size_t i = 0; i < idx::size; ++i) e = std::max(e, std::abs(y[i] - ref[i]));
  return e;
}

const std::vector<Method> kFixed = {Method::euler, Method::semi_implicit_euler, Method::rk4, Method::implicit_midpoint};
const std::vector<Method> kAdaptive = {Method::dopri5, Method::rosenbrock4, Method::switching};

IntegratorSettings fixed_settings(Method m, double dt) {
  IntegratorSettings s;
  s.method = m;
  s.dt = dt;
  return s;
}

IntegratorSettings adaptive_settings(Method m, double tol) {
  IntegratorSettings s;
  s.method = m;
  s.rtol = s.atol = tol;
  s.dt = 1e-3;
  return s;
}

std::unique_ptr<Stepper> started(const IntegratorSettings& s, double t0 = 0.0, const StateVector& y0 = exact(0.0)) {
  std::unique_ptr<Stepper> st = make_stepper(s, rates);
  st->reset(y0, t0);
  return st;
}

// The state at t_end: steps with t_limit = t_end and, if the last step passed it, reads the dense output.
StateVector run_to(Stepper& st, double t_end) {
  while (st.time() < t_end) st.step(t_end);
  StateVector y = st.state();
  if (st.time() > t_end) st.state_at(t_end, y);
  return y;
}

}  // namespace

// ---- order of convergence ----------------------------------------------------------------------------------------

namespace {

constexpr double kOrderTolerance = 0.2;  // the brief's band around the nominal order
constexpr double kOrderEndTime = 1.0;    // a multiple of every (dyadic) step below: runs land on it exactly

// Global error at kOrderEndTime with steps h. Adaptive methods are forced onto fixed steps h: max_dt = h and
// tolerances no error estimate can exceed, so every step is accepted and the controller's growth is capped at h.
double global_error(Method m, double h, std::uint64_t& steps) {
  IntegratorSettings s = fixed_settings(m, h);
  if (is_adaptive(m)) {
    s.max_dt = h;
    s.rtol = s.atol = 1e12;
  }
  std::unique_ptr<Stepper> st = started(s);
  while (st->time() < kOrderEndTime) st->step(kOrderEndTime);
  EXPECT_EQ(st->time(), kOrderEndTime) << to_string(m) << " h = " << h;  // dyadic steps sum exactly
  steps = st->stats.steps;
  return max_error(st->state(), exact(kOrderEndTime));
}

void expect_order(Method m, double h, double nominal) {
  SCOPED_TRACE(to_string(m));
  double e[3];
  for (int k = 0; k < 3; ++k) {
    const double hk = h / (1 << k);
    std::uint64_t steps = 0;
    e[k] = global_error(m, hk, steps);
    EXPECT_EQ(steps, static_cast<std::uint64_t>(std::llround(kOrderEndTime / hk))) << "not fixed steps of " << hk;
    note(std::string(to_string(m)) + ": global error at h = " + std::to_string(hk), e[k]);
  }
  for (int k = 0; k < 2; ++k) {
    const double order = std::log2(e[k] / e[k + 1]);
    note(std::string(to_string(m)) + ": observed order h/" + std::to_string(1 << k), order);
    EXPECT_NEAR(order, nominal, kOrderTolerance) << "errors " << e[k] << ", " << e[k + 1];
  }
}

// Error at the first step point at or past t_end (no interpolation) and the steps taken, at tolerance tol.
double tolerance_run(Method m, double tol, double t_end, double& steps) {
  std::unique_ptr<Stepper> st = started(adaptive_settings(m, tol));
  while (st->time() < t_end) st->step(t_end);
  steps = static_cast<double>(st->stats.steps);
  return max_error(st->state(), exact(st->time()));
}

}  // namespace

// Steps where the leading error term dominates: errors 1e-2 .. 7e-14, the smallest still ~10x the round-off of its
// 128 steps (sqrt(128) eps |y| ~ 5e-15); dopri5 at h = 1/8 is not yet asymptotic (orders 5.3, 5.15).
TEST(IntegratorOrder, EulerIsFirstOrder) { expect_order(Method::euler, 1.0 / 32, 1.0); }
TEST(IntegratorOrder, SemiImplicitEulerIsFirstOrder) { expect_order(Method::semi_implicit_euler, 1.0 / 32, 1.0); }
TEST(IntegratorOrder, Rk4IsFourthOrder) { expect_order(Method::rk4, 1.0 / 8, 4.0); }
TEST(IntegratorOrder, ImplicitMidpointIsSecondOrder) { expect_order(Method::implicit_midpoint, 1.0 / 16, 2.0); }
TEST(IntegratorOrder, Dopri5OnFixedStepsIsFifthOrder) { expect_order(Method::dopri5, 1.0 / 32, 5.0); }
TEST(IntegratorOrder, Rosenbrock4OnFixedStepsIsFourthOrder) { expect_order(Method::rosenbrock4, 1.0 / 8, 4.0); }
// Fewer than its 200 steps before the first rosenbrock4 probe: the switching method is dopri5 here.
TEST(IntegratorOrder, SwitchingOnFixedStepsIsFifthOrderWhileDopri5Runs) {
  expect_order(Method::switching, 1.0 / 32, 5.0);
}

// With the controller choosing the steps, error ~ C N^-p over N steps: p is the slope of log error against log steps.
// Both runs take > 100 steps, so the start-up ramp of a few steps biases the slope by < 0.1.
TEST(IntegratorOrder, AdaptiveErrorFallsWithTheStepCountAtTheNominalOrder) {
  const struct { Method m; double order; } cases[] = {{Method::dopri5, 5.0}, {Method::rosenbrock4, 4.0}};
  for (const auto& c : cases) {
    SCOPED_TRACE(to_string(c.m));
    double n1 = 0.0, n2 = 0.0;
    const double e1 = tolerance_run(c.m, 1e-7, 20.0, n1), e2 = tolerance_run(c.m, 1e-11, 20.0, n2);
    EXPECT_GT(n1, 100.0);
    const double slope = std::log(e1 / e2) / std::log(n2 / n1);
    const std::string name = to_string(c.m);
    note(name + ": steps at tol 1e-7", n1);
    note(name + ": steps at tol 1e-11", n2);
    note(name + ": error at tol 1e-7", e1);
    note(name + ": error at tol 1e-11", e2);
    note(name + ": -dlog(error)/dlog(steps)", slope);
    EXPECT_NEAR(slope, c.order, kOrderTolerance);
  }
}

// ---- dense output --------------------------------------------------------------------------------------------------

namespace {

constexpr double kDenseTol = 1e-8;  // rtol = atol of the adaptive runs below

// Error bound of an adaptive run at time t: on this non-expanding problem the global error grows by at most ~tol
// per unit time; 10x covers the interpolant and the controller's optimism.
double adaptive_bound(double t) { return 10.0 * kDenseTol * (1.0 + t); }

}  // namespace

TEST(IntegratorDenseOutput, AdaptiveInterpolantIsWithinTheToleranceAndContinuousAtStepEnds) {
  for (Method m : kAdaptive) {
    SCOPED_TRACE(to_string(m));
    std::unique_ptr<Stepper> st = started(adaptive_settings(m, kDenseTol));
    double worst = 0.0;
    while (st->time() < 5.0) {
      const StateVector before = st->state();
      st->step(5.0);
      const double t0 = st->previous_time(), t1 = st->time();
      ASSERT_LT(t0, t1);
      StateVector y;
      st->state_at(t0, y);
      StateVector start = before;
      normalize_figure_axis(start);  // state_at normalises f_hat; the stepper only once |f_hat|^2 drifts past 1e-10
      // The interpolant starts from the state the step started from, to round-off of its weights.
      EXPECT_LT(max_error(y, start), 1e-13) << "at t = " << t0;
      st->state_at(t1, y);
      EXPECT_EQ(y, st->state()) << "at t = " << t1;
      for (double theta : {0.25, 0.5, 0.75}) {
        const double t = t0 + theta * (t1 - t0);
        st->state_at(t, y);
        const double e = max_error(y, exact(t));
        worst = std::max(worst, e / adaptive_bound(t));
        EXPECT_LT(e, adaptive_bound(t)) << "at t = " << t;
      }
    }
    note(std::string(to_string(m)) + ": worst dense error / bound", worst);
  }
}

// Fixed-step state_at is documented as linear interpolation between the last two steps: exact at both ends, and
// off the exact solution by at most the ends' errors plus the chord's deviation h^2/8 max|y''|.
TEST(IntegratorDenseOutput, FixedStepInterpolationIsLinearBetweenTheLastTwoSteps) {
  const double h = 1.0 / 64;
  for (Method m : kFixed) {
    SCOPED_TRACE(to_string(m));
    std::unique_ptr<Stepper> st = started(fixed_settings(m, h));
    while (st->time() < 2.0) {
      const StateVector before = st->state();
      st->step(2.0);
      const double t0 = st->previous_time(), t1 = st->time();
      ASSERT_EQ(t1 - t0, st->last_step_size());
      StateVector y;
      st->state_at(t0, y);
      EXPECT_EQ(y, before);
      st->state_at(t1, y);
      EXPECT_EQ(y, st->state());
      const double ends = std::max(max_error(before, exact(t0)), max_error(st->state(), exact(t1)));
      for (double theta : {0.25, 0.5, 0.75}) {
        const double t = t0 + theta * h;
        st->state_at(t, y);
        EXPECT_LE(max_error(y, exact(t)), ends + h * h / 8.0 * kMaxSecondDerivative) << "at t = " << t;
      }
    }
  }
}

// ---- event location on the dense output ---------------------------------------------------------------------------

namespace {

struct Crossing {
  double t = std::numeric_limits<double>::quiet_NaN();
  double end_error = 0.0;  // largest error of g at the two step ends around the crossing
  double h = 0.0;          // that step's size
};

// Steps until g(state) changes sign, then bisects state_at over that step down to round-off.
Crossing locate(Stepper& st, const std::function<double(const StateVector&)>& g, double t_end) {
  Crossing c;
  while (st.time() < t_end) {
    const StateVector before = st.state();
    st.step(t_end);
    if ((g(before) > 0.0) == (g(st.state()) > 0.0)) continue;
    double lo = st.previous_time(), hi = st.time();
    c.h = hi - lo;
    c.end_error = std::max(std::abs(g(before) - g(exact(lo))), std::abs(g(st.state()) - g(exact(hi))));
    StateVector y;
    for (int i = 0; i < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon(); ++i) {
      const double mid = 0.5 * (lo + hi);
      st.state_at(mid, y);
      ((g(y) > 0.0) == (g(before) > 0.0) ? lo : hi) = mid;
    }
    c.t = 0.5 * (lo + hi);
    return c;
  }
  return c;
}

}  // namespace

// Zero crossings of known functions g of the state: omega_x = e^-t passes 1/2 at ln 2 (slope -1/2), the gap cos t
// passes 0 at pi/2 (slope -1); |g''| <= 1 for both. An error e in g moves the located time by at most e over the
// least |g'| within a step h of the crossing, which is >= |slope| (1 - h) for both.
TEST(IntegratorEvents, BisectionOnTheDenseOutputFindsTheExactCrossingTime) {
  const struct { const char* what; std::function<double(const StateVector&)> g; double t_star, slope; } events[] = {
      {"omega_x = 1/2", [](const StateVector& y) { return y[idx::omega] - 0.5; }, std::log(2.0), 0.5},
      {"gap = 0", [](const StateVector& y) { return y[idx::gap]; }, 0.5 * kPi, 1.0}};
  for (const auto& ev : events) {
    for (Method m : {Method::euler, Method::semi_implicit_euler, Method::rk4, Method::dopri5, Method::rosenbrock4,
                     Method::switching}) {
      SCOPED_TRACE(std::string(to_string(m)) + ", " + ev.what);
      const double h = 1.0 / 64;
      std::unique_ptr<Stepper> st = started(is_adaptive(m) ? adaptive_settings(m, kDenseTol) : fixed_settings(m, h));
      const Crossing c = locate(*st, ev.g, 3.0);
      ASSERT_TRUE(std::isfinite(c.t)) << "no crossing found";
      // Adaptive: the dense-output bound; fixed: the linear-interpolation bound with |g''| <= 1.
      const double e = is_adaptive(m) ? adaptive_bound(ev.t_star) : c.end_error + c.h * c.h / 8.0;
      const double bound = e / (ev.slope * (1.0 - c.h));
      EXPECT_NEAR(c.t, ev.t_star, bound);
      note(std::string(to_string(m)) + ", " + ev.what + ": located - exact [s]", c.t - ev.t_star);
    }
  }
}

// ---- restart after an event ---------------------------------------------------------------------------------------

namespace {

IntegratorSettings settings_for(Method m) {
  return is_adaptive(m) ? adaptive_settings(m, kDenseTol) : fixed_settings(m, 1.0 / 64);
}

// reset() starts afresh at (y, t): no interval behind it, the clock and the step counts carry on.
void expect_fresh_start(const Stepper& st, const StateVector& y, double t, std::uint64_t steps) {
  EXPECT_EQ(st.time(), t);
  EXPECT_EQ(st.previous_time(), t);
  EXPECT_EQ(st.state(), y);
  StateVector at;
  st.state_at(t, at);
  EXPECT_EQ(at, y);
  EXPECT_EQ(st.stats.steps, steps);
}

}  // namespace

// Mid-run, an event replaces the state with exact(s) (not on the old trajectory): the continuation must follow
// exact(t - t1 + s), and a fixed-step method must continue exactly like a stepper started there.
TEST(IntegratorRestart, AfterResetTheRunFollowsTheExactSolutionFromTheNewState) {
  const double s = 0.3, t_run = 2.0;
  for (Method m : {Method::euler, Method::semi_implicit_euler, Method::rk4, Method::dopri5, Method::rosenbrock4,
                   Method::switching}) {
    SCOPED_TRACE(to_string(m));
    std::unique_ptr<Stepper> st = started(settings_for(m));
    run_to(*st, 1.0);
    const double t1 = st->time();
    const std::uint64_t steps = st->stats.steps, rhs = st->stats.rhs_evaluations;
    st->reset(exact(s), t1);
    expect_fresh_start(*st, exact(s), t1, steps);
    const StateVector y = run_to(*st, t1 + t_run);
    EXPECT_GT(st->stats.steps, steps);
    EXPECT_GT(st->stats.rhs_evaluations, rhs);
    if (is_adaptive(m)) {
      EXPECT_LT(max_error(y, exact(s + t_run)), adaptive_bound(t_run));
    } else {
      std::unique_ptr<Stepper> fresh = started(settings_for(m), t1, exact(s));
      EXPECT_EQ(y, run_to(*fresh, t1 + t_run));
      EXPECT_EQ(st->stats.steps - steps, fresh->stats.steps);
    }
  }
}

// ---- the stiff layer ------------------------------------------------------------------------------------------------

namespace {

// The layer: omega_x = e^-t in [0.3, 0.6] (t in [0.51, 1.20]), widened to [0.25, 0.65] while inside (hysteresis).
bool in_layer(const StateVector& y, bool inside) {
  const double w = y[idx::omega];
  return inside ? (w > 0.25 && w < 0.65) : (w > 0.3 && w < 0.6);
}

struct LayerRun {
  std::uint64_t layer_steps = 0;  // steps that started in the layer
  double first_layer_step = 0.0;  // size of the first of them [s]
};

// Runs to t_end, checking the dense output of every step and counting the steps whose start state was in the
// layer (the hand-over happens at the start of the next step, so those are the rosenbrock4 steps). A fixed-step
// primary interpolates linearly outside the layer: its chord adds h^2/8 max|y''| there.
LayerRun run_across_layer(Stepper& st, double t_end, double bound, bool linear_primary) {
  LayerRun run;
  bool inside = in_layer(st.state(), false);
  while (st.time() < t_end) {
    st.step(t_end);
    const double h = st.last_step_size();
    if (inside && run.layer_steps++ == 0) run.first_layer_step = h;
    const double chord = linear_primary && !inside ? h * h / 8.0 * kMaxSecondDerivative : 0.0;
    inside = in_layer(st.state(), inside);
    StateVector y;
    const double t = st.previous_time() + 0.5 * h;
    st.state_at(t, y);
    EXPECT_LT(max_error(y, exact(t)), bound + chord) << "mid-step at t = " << t;
  }
  return run;
}

}  // namespace

TEST(IntegratorLayer, RosenbrockStepsTheLayerAndTheSolutionStaysExactAcrossBothHandOvers) {
  for (Method m : {Method::dopri5, Method::rk4, Method::switching}) {
    SCOPED_TRACE(to_string(m));
    const IntegratorSettings s = settings_for(m);
    std::unique_ptr<Stepper> st = make_stepper(s, rates, {}, in_layer);
    st->reset(exact(0.0), 0.0);
    // The layer's rosenbrock4 runs at kDenseTol; rk4 at h = 1/64 errs ~h^4 = 6e-8 at most, well inside this bound.
    const double bound = adaptive_bound(2.0);
    const LayerRun run = run_across_layer(*st, 2.0, bound, !is_adaptive(m));
    EXPECT_GT(run.layer_steps, 0u);
    EXPECT_EQ(st->layer_steps(), run.layer_steps);
    // rosenbrock4 enters the layer with its documented first step (rounding of t + 1e-9 aside).
    EXPECT_NEAR(run.first_layer_step, kLayerFirstStep, 1e-15);
    EXPECT_LT(st->layer_steps(), st->stats.steps);
    EXPECT_LT(max_error(st->state(), exact(st->time())), bound);
    note(std::string(to_string(m)) + " with a layer: layer steps", static_cast<double>(st->layer_steps()));
    // A reset into the layer hands the next step to rosenbrock4 at once.
    const std::uint64_t before = st->layer_steps();
    st->reset(exact(0.9), st->time());
    st->step(st->time() + 1.0);
    EXPECT_EQ(st->layer_steps(), before + 1);
  }
}

// ---- counts -------------------------------------------------------------------------------------------------------

// Right-hand sides per step: Euler 1, semi-implicit Euler 2 (velocities, then positions with the new velocities),
// RK4 4 stages; every run of T / dt steps lands on T.
TEST(IntegratorCounts, FixedStepMethodsEvaluateTheirStagesOncePerStep) {
  const struct { Method m; std::uint64_t per_step; } cases[] = {
      {Method::euler, 1}, {Method::semi_implicit_euler, 2}, {Method::rk4, 4}};
  for (const auto& c : cases) {
    SCOPED_TRACE(to_string(c.m));
    std::unique_ptr<Stepper> st = started(fixed_settings(c.m, 1.0 / 64));
    run_to(*st, 1.0);
    EXPECT_EQ(st->time(), 1.0);
    EXPECT_EQ(st->stats.steps, 64u);
    EXPECT_EQ(st->stats.rhs_evaluations, c.per_step * st->stats.steps);
    EXPECT_EQ(st->stats.rejected, 0u);
  }
}

// Sampling must not change a fixed-step run: advancing to every multiple of dt (2 ms, not a binary fraction) or to
// every 10 ms makes the same T / dt steps of h = dt as one run to T, and ends on the same bits. A time kept as a sum
// of steps drifts by ulps from k dt: a sample then costs an extra step of a few ulps, or a step a few ulps short.
TEST(IntegratorCounts, FixedStepRunsSampledAtMultiplesOfDtMakeTheSameSteps) {
  const double dt = 2e-3, t_end = 5.0;
  for (Method m : kFixed) {
    SCOPED_TRACE(to_string(m));
    std::unique_ptr<Stepper> whole = started(fixed_settings(m, dt));
    const StateVector y_whole = run_to(*whole, t_end);
    for (double interval : {dt, 5 * dt}) {
      std::unique_ptr<Stepper> sampled = started(fixed_settings(m, dt));
      StateVector y{};
      const long n = std::lround(t_end / interval);
      for (long k = 1; k <= n; ++k) y = run_to(*sampled, static_cast<double>(k) * interval);
      EXPECT_EQ(sampled->stats.steps, 2500u) << "samples every " << interval;
      EXPECT_EQ(whole->stats.steps, 2500u);
      EXPECT_EQ(sampled->time(), t_end);
      EXPECT_EQ(std::memcmp(y.data(), y_whole.data(), sizeof y), 0) << "samples every " << interval << ": "
                                                                        << max_error(y, y_whole);
    }
  }
}

// A first step of 1 s errs ~1e-3 here, far beyond tol 1e-10: the controller must reject it, and the stats say so.
TEST(IntegratorCounts, AdaptiveMethodsCountTheStepsTheyReject) {
  for (Method m : kAdaptive) {
    SCOPED_TRACE(to_string(m));
    IntegratorSettings s = adaptive_settings(m, 1e-10);
    s.dt = 1.0;
    std::unique_ptr<Stepper> st = started(s);
    st->step(10.0);
    EXPECT_EQ(st->stats.steps, 1u);
    EXPECT_GE(st->stats.rejected, 1u);
    EXPECT_LT(st->last_step_size(), 0.5);
    // dopri5 (first same as last): one start derivative, 6 stages per attempt, 1 more if f_hat was renormalised.
    const std::uint64_t attempts = st->stats.steps + st->stats.rejected;
    if (m != Method::rosenbrock4) {
      EXPECT_GE(st->stats.rhs_evaluations, 1 + 6 * attempts);
      EXPECT_LE(st->stats.rhs_evaluations, 2 + 6 * attempts);
    }
    note(std::string(to_string(m)) + ": rejected first steps", static_cast<double>(st->stats.rejected));
  }
}

// Constant rates: every method is exact after one step, so each component with a non-zero rate moves by dt * rate
// (f_hat, renormalised after each step, gets rate 0).
TEST(IntegratorSteps, OneStepOfConstantRatesMovesEveryComponent) {
  const System constant = [](const StateVector&, StateVector& d) {
    for (std::size_t i = 0; i < idx::size; ++i) d[i] = 0.1 * static_cast<double>(i + 1);
    d[idx::f] = d[idx::f + 1] = d[idx::f + 2] = 0.0;
  };
  for (Method m : {Method::euler, Method::semi_implicit_euler, Method::rk4, Method::dopri5, Method::rosenbrock4,
                   Method::switching}) {
    SCOPED_TRACE(to_string(m));
    IntegratorSettings s = fixed_settings(m, 0.01);
    s.max_dt = 0.01;  // the adaptive methods' first step, and no larger
    std::unique_ptr<Stepper> st = make_stepper(s, constant);
    StateVector y0{};
    y0[idx::f + 2] = 1.0;
    st->reset(y0, 0.0);
    st->step(1.0);
    ASSERT_EQ(st->time(), 0.01);
    StateVector d;
    constant(y0, d);
    for (std::size_t i = 0; i < idx::size; ++i)
      EXPECT_NEAR(st->state()[i], y0[i] + 0.01 * d[i], 1e-15) << "component " << i;
  }
}

// ---- switching to rosenbrock4 on a stiff problem -------------------------------------------------------------------

namespace {

constexpr double kStiffness = 1e4;  // 1/s: dopri5's stability limits its step to ~3.3 / kStiffness

// rates() with omega_z relaxing at kStiffness onto u_x = cos t; its slow solution, taken as the start, is
// omega_z = (k^2 cos t + k sin t) / (1 + k^2), with no transient to resolve.
void stiff_rates(const StateVector& y, StateVector& d) {
  rates(y, d);
  d[idx::omega + 2] = -kStiffness * (y[idx::omega + 2] - y[idx::u]);
}

StateVector stiff_exact(double t) {
  const double k = kStiffness;
  StateVector y = exact(t);
  y[idx::omega + 2] = (k * k * std::cos(t) + k * std::sin(t)) / (1.0 + k * k);
  return y;
}

}  // namespace

// After its first 200 dopri5 steps the switching method probes rosenbrock4, whose steps are no longer bounded by
// stability, and keeps it: far fewer steps than dopri5 alone, at the same accuracy.
TEST(IntegratorSwitching, HandsAStiffProblemToRosenbrock4AndStaysAccurate) {
  const double t_end = 2.0;
  std::uint64_t steps[2];
  int k = 0;
  for (Method m : {Method::dopri5, Method::switching}) {
    SCOPED_TRACE(to_string(m));
    std::unique_ptr<Stepper> st = make_stepper(adaptive_settings(m, kDenseTol), stiff_rates);
    st->reset(stiff_exact(0.0), 0.0);
    while (st->time() < t_end) {
      st->step(t_end);
      StateVector y;
      const double t = st->previous_time() + 0.5 * st->last_step_size();
      st->state_at(t, y);
      ASSERT_LT(max_error(y, stiff_exact(t)), adaptive_bound(t)) << "mid-step at t = " << t;
    }
    EXPECT_LT(max_error(st->state(), stiff_exact(st->time())), adaptive_bound(st->time()));
    steps[k++] = st->stats.steps;
    note(std::string("stiff problem, ") + to_string(m) + ": steps", static_cast<double>(st->stats.steps));
  }
  // dopri5 needs >= t_end kStiffness / 3.3 = 6000 steps; rosenbrock4 takes steps limited by accuracy alone.
  EXPECT_GT(steps[0], 5000u);
  EXPECT_LT(steps[1], steps[0] / 4);
}

// ---- event location through the Simulator ---------------------------------------------------------------------------

namespace {

// The ball of contact_modes_test (m 0.1 kg, R 1 cm) dropped from gap h0 onto a level frictionless plane.
std::vector<ModeSwitch> ball_drop(const std::string& integrator, double h0, double t_end) {
  const std::string yaml =
      "top: {mass: 0.1, tip_radius: 0.01, com_offset: 0.0, inertia_axial: 4.0e-6, inertia_transverse: 4.0e-6}\n"
      "plane: {inclination: 0.0, gravity: 9.81}\nfriction: {law: coulomb, mu: 0.0}\n"
      "initial: {tilt: 0.0, spin: 0.0, gap: " + top_sim_test::num(h0) + "}\nintegrator: " + integrator + "\n";
  Simulator sim(top_sim_test::scene_from(yaml));
  sim.advance_to(t_end);
  return sim.take_mode_switches();
}

}  // namespace

// Free fall gap(t) = h0 - g t^2 / 2 touches down at sqrt(2 h0 / g). The scan bisects the dense output, so each
// method's located time carries its known bias: Euler's gap lags by g t dt / 2 (late by dt / 2), semi-implicit
// Euler's leads by as much (early by dt / 2), RK4 is exact on a quadratic and only the chord of the linear
// interpolation crosses early by <= dt^2 / (8 t); rosenbrock4's height error ~ atol + rtol h0 over the impact speed.
TEST(IntegratorEvents, SimulatorLocatesTheBallTouchdownWithEachMethodsKnownBias) {
  const double g = 9.81, h0 = 0.02, dt = 1e-4;
  const double t_drop = std::sqrt(2.0 * h0 / g);
  const struct { const char* integrator; double expected, tolerance; } cases[] = {
      {"{method: euler, dt: 1.0e-4}", t_drop + 0.5 * dt, dt * dt / t_drop},
      {"{method: semi_implicit_euler, dt: 1.0e-4}", t_drop - 0.5 * dt, dt * dt / t_drop},
      {"{method: rk4, dt: 1.0e-4}", t_drop, dt * dt / (8.0 * t_drop) + 1e-12},
      {"{method: rosenbrock4, rtol: 1.0e-8, atol: 1.0e-10}", t_drop, 10.0 * (1e-10 + 1e-8 * h0) / (g * t_drop)}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.integrator);
    const std::vector<ModeSwitch> sw = ball_drop(c.integrator, h0, 1.1 * t_drop);
    ASSERT_FALSE(sw.empty()) << "no touchdown by 1.1 t_drop";
    EXPECT_EQ(sw[0].kind, ModeSwitchKind::touchdown);
    EXPECT_NEAR(sw[0].t, c.expected, c.tolerance);
    note(std::string(c.integrator) + ": touchdown - t_drop [s]", sw[0].t - t_drop);
  }
}

// ---- dopri5 against odeint's own algebra, and the first-same-as-last state ----------------------------------------

namespace {

// rates() with f_hat held at e_z and psi at 0: the stepper never renormalises, and psi (left out of the stepper's
// error norm) has a zero error estimate, so odeint's default error checker sees the same maximum.
void rates_fixed_axis(const StateVector& y, StateVector& d) {
  rates(y, d);
  d[idx::f] = d[idx::f + 1] = d[idx::f + 2] = 0.0;
  d[idx::psi] = 0.0;
}

}  // namespace

// The stepper's dopri5 makes its linear combinations two components at a time: the same IEEE operations on each
// component as odeint's array algebra, so every step and interpolated state equals odeint's bit for bit. Steps of
// max_dt under tolerances no error reaches: both step-size controllers (the stepper's PI, odeint's) keep h = max_dt.
TEST(IntegratorDopri5, StepsEqualOdeintsArrayAlgebraBitForBit) {
  namespace odeint = boost::numeric::odeint;
  IntegratorSettings s = adaptive_settings(Method::dopri5, 1e12);
  s.dt = s.max_dt = 1.0 / 64;
  StateVector y0 = exact(0.0);
  y0[idx::f] = y0[idx::f + 1] = 0.0;
  y0[idx::f + 2] = 1.0;
  y0[idx::psi] = 0.0;
  std::unique_ptr<Stepper> st = make_stepper(s, rates_fixed_axis);
  st->reset(y0, 0.0);
  auto ref = odeint::make_dense_output(s.atol, s.rtol, s.max_dt, odeint::runge_kutta_dopri5<StateVector>());
  ref.initialize(y0, 0.0, s.dt);
  const auto sys = [](const StateVector& y, StateVector& d, double) { rates_fixed_axis(y, d); };
  for (int k = 0; k < 200; ++k) {
    st->step(1e9);
    ref.do_step(sys);
    ASSERT_EQ(st->time(), ref.current_time()) << "step " << k;
    ASSERT_EQ(0, std::memcmp(st->state().data(), ref.current_state().data(), sizeof(StateVector))) << "step " << k;
    StateVector a, b;
    const double mid = 0.5 * (st->previous_time() + st->time());
    st->state_at(mid, a);
    ref.calc_state(mid, b);
    ASSERT_EQ(0, std::memcmp(a.data(), b.data(), sizeof(StateVector))) << "step " << k;
  }
  EXPECT_GT(st->time(), 1.0);
}

// Whenever a stepper says its state was the last right-hand side's argument, it was, in every bit (the simulator
// then reuses that evaluation's contact force); dopri5 says so after most steps, never right after a reset or a
// renormalisation of f_hat (rates() turns f_hat, so it drifts), and fixed-step methods never do.
TEST(IntegratorDopri5, StateWasLastRhsOnlyWhenItWas) {
  for (Method m : {Method::dopri5, Method::switching, Method::rk4}) {
    SCOPED_TRACE(to_string(m));
    StateVector last{};
    const System recording = [&last](const StateVector& y, StateVector& d) {
      last = y;
      rates(y, d);
    };
    IntegratorSettings s = is_adaptive(m) ? adaptive_settings(m, 1e-9) : fixed_settings(m, 1e-2);
    std::unique_ptr<Stepper> st = make_stepper(s, recording);
    st->reset(exact(0.0), 0.0);
    EXPECT_FALSE(st->state_was_last_rhs());
    int said = 0, steps = 0;
    for (; st->time() < 20.0; ++steps) {
      st->step(1e9);
      if (!st->state_was_last_rhs()) continue;
      ++said;
      ASSERT_EQ(0, std::memcmp(last.data(), st->state().data(), sizeof(StateVector))) << "t = " << st->time();
    }
    if (m == Method::rk4) {
      EXPECT_EQ(said, 0);
    } else {
      EXPECT_GT(said, steps / 2);
    }
    note(std::string(to_string(m)) + ": steps whose state was the last RHS argument", said);
    note(std::string(to_string(m)) + ": steps", steps);
  }
}

// Renormalising f_hat (rates() turns it, so its length drifts) keeps dopri5's first-same-as-last derivative: every
// right-hand side is a stage of a tried step (6 each, 1 to start), none re-initialises, and after 20 s the state is
// within 100 times the tolerance of the exact solution (measured 1.5e-9).
TEST(IntegratorDopri5, RenormalisingKeepsTheLastDerivative) {
  std::unique_ptr<Stepper> st = started(adaptive_settings(Method::dopri5, 1e-9));
  int renormalised = 0;
  while (st->time() < 20.0) {
    st->step(20.0);
    if (!st->state_was_last_rhs()) ++renormalised;
  }
  EXPECT_GT(renormalised, 0);
  EXPECT_EQ(st->stats.rhs_evaluations, 1 + 6 * (st->stats.steps + st->stats.rejected));
  EXPECT_LT(max_error(st->state(), exact(st->time())), 1e-7);
  note("dopri5, 20 s: renormalised steps", renormalised);
  note("dopri5, 20 s: error", max_error(st->state(), exact(st->time())));
}

// The PI controller lets no step grow right after a rejection (Hairer's DOPRI5): a first step of 1 s is rejected
// here (see AdaptiveMethodsCountTheStepsTheyReject), so the second step is at most the first accepted one.
TEST(IntegratorDopri5, NoGrowthRightAfterARejection) {
  IntegratorSettings s = adaptive_settings(Method::dopri5, 1e-10);
  s.dt = 1.0;
  std::unique_ptr<Stepper> st = started(s);
  st->step(10.0);
  ASSERT_GE(st->stats.rejected, 1u);
  const double h1 = st->last_step_size();
  st->step(10.0);  // tried at the proposal (<= h1) or, if rejected, smaller still
  EXPECT_LE(st->last_step_size(), h1);
  note("dopri5: first accepted step after rejections [s]", h1);
}
