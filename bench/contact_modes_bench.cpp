// Google Benchmark of the contact modes (physics.md section 9; issue 9's targets): the Coulomb scene at the default
// regularisation with every integrator, the hopping scene, and the cost of the in-step event sampling.
// A benchmark, not a test: it reports times and counters and never fails on them (docs/performance.md).
#include <benchmark/benchmark.h>

#include <string>

#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;

Scene scene_named(const std::string& name) {
  return load_scene(default_config_dir() + "/scenes/" + name + ".yaml");
}

// A whole scene run; counters: steps, rosenbrock4 steps across the slip-onset layer, mode switches.
void run_scene(benchmark::State& bs, const Scene& scene, double duration) {
  std::string fault;
  StepperStats stats;
  std::uint64_t layer = 0, switches = 0;
  for (auto _ : bs) {
    Simulator sim(scene);
    sim.advance_to(duration);
    stats = sim.stats();
    layer = sim.layer_steps();
    switches = sim.mode_switch_count();
    if (sim.fault() != ContactFault::none) fault = sim.fault_message();
  }
  if (!fault.empty()) bs.SkipWithError(fault.c_str());
  bs.counters["steps"] = static_cast<double>(stats.steps);
  bs.counters["layer_steps"] = static_cast<double>(layer);
  bs.counters["switches"] = static_cast<double>(switches);
  bs.counters["sim_s"] = duration;
}

// Coulomb mu 0.3, v_eps 1e-9, 5 s, each method (fixed steps at their stability limits at 200 rad/s).
void coulomb(benchmark::State& bs, Method method, double dt) {
  Scene scene = scene_named("coulomb");
  scene.integrator.method = method;
  scene.integrator.dt = dt;
  run_scene(bs, scene, 5.0);
}
BENCHMARK_CAPTURE(coulomb, dopri5, Method::dopri5, 1e-4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(coulomb, rosenbrock4, Method::rosenbrock4, 1e-4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(coulomb, switching, Method::switching, 1e-4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(coulomb, rk4_dt3e-4, Method::rk4, 3e-4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(coulomb, euler_dt1e-5, Method::euler, 1e-5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(coulomb, semi_implicit_euler_dt1e-5, Method::semi_implicit_euler, 1e-5)
    ->Unit(benchmark::kMillisecond);

// The hopping scene (5000 rad/s, restitution 0.5) for 0.5 s; and with the step capped at 2 us instead of the
// in-step event sampling (the alternative physics.md section 9 offers): the price of each choice.
void hopping(benchmark::State& bs, double max_dt) {
  Scene scene = scene_named("hopping");
  scene.integrator.max_dt = max_dt;
  run_scene(bs, scene, 0.5);
}
BENCHMARK_CAPTURE(hopping, sampled, 0.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(hopping, step_capped_2us, 2e-6)->Unit(benchmark::kMillisecond);
// The cap physics.md suggests (1/40 of the nutation period 2 pi I_d / (I_f omega) = 19 us at 5000 rad/s).
BENCHMARK_CAPTURE(hopping, step_capped_19us, 1.9e-5)->Unit(benchmark::kMillisecond);

// The scenes of issue 9: the default 300 s (must not be slower than before the contact modes), the ball.
void scene_run(benchmark::State& bs, const char* name, double duration) { run_scene(bs, scene_named(name), duration); }
BENCHMARK_CAPTURE(scene_run, default_300s, "default", 300.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(scene_run, ball_1s, "ball", 1.0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
