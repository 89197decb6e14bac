// Google Benchmark of the core: one right-hand side per model, one simulated second per integrator.
// A benchmark, not a test: it reports times and counters and never fails on them (docs/performance.md).
#include <benchmark/benchmark.h>

#include <string>

#include "top_sim/dynamics.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;

Scene default_scene() { return load_scene(default_config_dir() + "/scenes/default.yaml"); }

// A nutating state (default scene after 0.37 s): every term of the right-hand side is non-trivial there.
StateVector nutating_state(const Scene& scene) {
  Simulator sim(scene);
  sim.advance_to(0.37);
  return sim.state();
}

void rhs(benchmark::State& bs, NormalForceModel normal_force, ModelKind kind) {
  Scene scene = default_scene();
  scene.model.normal_force = normal_force;
  const StateVector y = nutating_state(scene);
  scene.model.kind = kind;
  StateVector dydt{};
  for (auto _ : bs) {
    benchmark::DoNotOptimize(y);
    model_derivative(scene.model, ContactMode::slipping, y, dydt);
    benchmark::DoNotOptimize(dydt);
  }
}
BENCHMARK_CAPTURE(rhs, full_constrained, NormalForceModel::constrained, ModelKind::full);
BENCHMARK_CAPTURE(rhs, full_static, NormalForceModel::static_approximation, ModelKind::full);
BENCHMARK_CAPTURE(rhs, adiabatic, NormalForceModel::constrained, ModelKind::adiabatic);

// The frictionless top (config/scenes/frictionless.yaml, Coulomb mu = 0) at 0.37 s: the lean-step scene of issue 21.
void rhs_frictionless(benchmark::State& bs) {
  const Scene scene = load_scene(default_config_dir() + "/scenes/frictionless.yaml");
  const StateVector y = nutating_state(scene);
  StateVector dydt{};
  for (auto _ : bs) {
    benchmark::DoNotOptimize(y);
    model_derivative(scene.model, ContactMode::slipping, y, dydt);
    benchmark::DoNotOptimize(dydt);
  }
}
BENCHMARK(rhs_frictionless);

// The finite contact of physics.md section 12 at the same nutating state (issue 32: at most 1.3x the point
// contact's right-hand side). `terms`: 0 fixed patch, 1 Hertz patch, 2 Hertz patch with the elliptic law,
// 3 Hertz patch with rolling resistance and air.
void rhs_finite(benchmark::State& bs, int terms) {
  Scene scene = default_scene();
  const StateVector y = nutating_state(scene);
  FiniteContact& fc = scene.model.finite_contact;
  if (terms == 0) {
    fc.patch_radius = 1.0e-4;
  } else {
    fc.hertz = true;
    fc.effective_modulus = effective_modulus({6.9e10, 0.33}, {3.0e9, 0.37});
  }
  if (terms == 2) fc.law = DrillingLaw::elliptic;
  if (terms == 3) {
    fc.rolling_resistance = 1.0e-5;
    scene.model.air.spin_drag = 1.0e-8;
    scene.model.air.drag = 1.0e-3;
  }
  StateVector dydt{};
  model_derivative(scene.model, ContactMode::slipping, y, dydt);  // builds the exact law's table outside the timing
  for (auto _ : bs) {
    benchmark::DoNotOptimize(y);
    model_derivative(scene.model, ContactMode::slipping, y, dydt);
    benchmark::DoNotOptimize(dydt);
  }
}
BENCHMARK_CAPTURE(rhs_finite, fixed_patch_exact, 0);
BENCHMARK_CAPTURE(rhs_finite, hertz_exact, 1);
BENCHMARK_CAPTURE(rhs_finite, hertz_elliptic, 2);
BENCHMARK_CAPTURE(rhs_finite, hertz_exact_rolling_air, 3);

// One simulated second of the default scene from its tilted start (the transient: the hardest second).
// Fixed steps: the largest power-of-ten-ish step that stays bounded at 200 rad/s (stability map, docs/performance.md).
void simulated_second(benchmark::State& bs, Method method, double dt, double t0) {
  Scene scene = default_scene();
  scene.integrator.method = method;
  scene.integrator.dt = dt;
  StepperStats stats;
  std::string fault;
  for (auto _ : bs) {
    bs.PauseTiming();
    Simulator sim(scene);
    if (t0 > 0.0) sim.advance_to(t0);
    const StepperStats before = sim.stats();
    bs.ResumeTiming();
    sim.advance_to(t0 + 1.0);
    stats.steps = sim.stats().steps - before.steps;
    stats.rhs_evaluations = sim.stats().rhs_evaluations - before.rhs_evaluations;
    if (sim.fault() != ContactFault::none) fault = sim.fault_message();
  }
  if (!fault.empty()) bs.SkipWithError(fault.c_str());
  bs.counters["steps_per_sim_s"] = static_cast<double>(stats.steps);
  bs.counters["rhs_per_sim_s"] = static_cast<double>(stats.rhs_evaluations);
}
BENCHMARK_CAPTURE(simulated_second, euler_dt1e-3, Method::euler, 1e-3, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulated_second, semi_implicit_euler_dt1e-3, Method::semi_implicit_euler, 1e-3, 0.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulated_second, rk4_dt3e-3, Method::rk4, 3e-3, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulated_second, dopri5, Method::dopri5, 1e-4, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulated_second, rosenbrock4, Method::rosenbrock4, 1e-4, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(simulated_second, switching, Method::switching, 1e-4, 0.0)->Unit(benchmark::kMillisecond);

// Whole runs against the issue-5 targets: 10 s including the transient, the 300 s relaxation, and 300 s asleep.
void whole_run(benchmark::State& bs, Method method, double duration, bool asleep) {
  Scene scene = default_scene();
  scene.integrator.method = method;
  if (asleep) scene.initial.start = StartKind::stationary;
  StepperStats stats;
  for (auto _ : bs) {
    Simulator sim(scene);
    sim.advance_to(duration);
    stats = sim.stats();
  }
  bs.counters["steps"] = static_cast<double>(stats.steps);
  bs.counters["rhs"] = static_cast<double>(stats.rhs_evaluations);
  bs.counters["sim_s"] = duration;
}
BENCHMARK_CAPTURE(whole_run, dopri5_10s, Method::dopri5, 10.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(whole_run, dopri5_300s, Method::dopri5, 300.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(whole_run, switching_300s, Method::switching, 300.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(whole_run, dopri5_asleep_300s, Method::dopri5, 300.0, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(whole_run, rosenbrock4_asleep_300s, Method::rosenbrock4, 300.0, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(whole_run, switching_asleep_300s, Method::switching, 300.0, true)->Unit(benchmark::kMillisecond);

// The C++ side of bench/python_bench.py: one short advance (0.1 ms, about one step) plus a snapshot, and a
// snapshot alone, on a top that has run 10 s (what Python's sim.run(1e-4) and sim.snapshot() wrap).
void short_advance_and_snapshot(benchmark::State& bs, bool advance) {
  Simulator sim(default_scene());
  sim.advance_to(10.0);
  double t = sim.time();
  for (auto _ : bs) {
    if (advance) sim.advance_to(t += 1e-4);
    benchmark::DoNotOptimize(sim.snapshot());
  }
}
BENCHMARK_CAPTURE(short_advance_and_snapshot, advance_1e-4_and_snapshot, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(short_advance_and_snapshot, snapshot_only, false)->Unit(benchmark::kMicrosecond);

// The per-step bookkeeping the switching method charges rosenbrock4 (kStiffOverhead): one step's CPU on a
// sleeping state, to compare with rhs/full_constrained times its right-hand sides per step.
void rosenbrock_step_asleep(benchmark::State& bs) {
  Scene scene = default_scene();
  scene.initial.start = StartKind::stationary;
  scene.integrator.method = Method::rosenbrock4;
  scene.integrator.max_dt = 1e-2;  // a fixed step size keeps each step's work the same
  Model model = scene.model;
  auto stepper = make_stepper(scene.integrator, [&model](const StateVector& y, StateVector& d) {
    model_derivative(model, ContactMode::slipping, y, d);
  });
  stepper->reset(initial_state(scene), 0.0);
  for (auto _ : bs) stepper->step(1e9);
  bs.counters["rhs_per_step"] = static_cast<double>(stepper->stats.rhs_evaluations) /
                                static_cast<double>(stepper->stats.steps);
}
BENCHMARK(rosenbrock_step_asleep);

}  // namespace

BENCHMARK_MAIN();
