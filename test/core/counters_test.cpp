// Deterministic counters that fail when bookkeeping creeps into the hot path (issue 21's guard; timings live in
// bench/, never here): right-hand sides per dopri5 step and heap allocations while stepping. The counting
// operator new below replaces the global one for this whole test binary (it only counts).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

#include "test_util.hpp"
#include "../../src/core/counters.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

#include "../../bench/counting_new.hpp"  // replaces the global operator new for this whole test binary

namespace {

top_sim::Simulator* warmed(const std::string& scene) {
  auto* sim = new top_sim::Simulator(top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/" + scene));
  EXPECT_TRUE(sim->advance_to(1.4));  // past the start's transient (stepper set-up, first events, impacts)
  return sim;
}

}  // namespace

// dopri5 evaluates six right-hand sides per step tried (first-same-as-last), accepted or rejected; only a restart
// after a located event adds any. On event-free stretches (the default top precessing towards sleep, the hopping top
// after its hops) the count is exactly 6 (steps + rejected), measured at HEAD: +0 over 1 s each. A dynamics
// evaluation added to the step's bookkeeping would add one per step.
TEST(Counters, Dopri5MakesAtMostSixRightHandSidesPerStepTried) {
  for (const char* scene : {"default.yaml", "hopping.yaml"}) {
    std::unique_ptr<top_sim::Simulator> sim(warmed(scene));
    const top_sim::StepperStats before = sim->stats();
    ASSERT_TRUE(sim->advance_to(sim->time() + 1.0));
    const top_sim::StepperStats after = sim->stats();
    const std::uint64_t tried = (after.steps - before.steps) + (after.rejected - before.rejected);
    ASSERT_GT(after.steps - before.steps, 100u) << scene;
    EXPECT_LE(after.rhs_evaluations - before.rhs_evaluations, 6 * tried + 2)
        << scene << ": " << after.rhs_evaluations - before.rhs_evaluations << " right-hand sides for " << tried
        << " steps tried";
  }
}

// Stepping allocates nothing: one advance over many steps (and 10 regime cadence points) allocates nothing and
// builds no sample at its end (a sample's stationary solve may allocate a root list for some laws).
TEST(Counters, NoHeapAllocationWhileStepping) {
  for (const char* scene : {"default.yaml", "hopping.yaml", "coulomb.yaml"}) {
    std::unique_ptr<top_sim::Simulator> sim(warmed(scene));
    const std::uint64_t steps_before = sim->stats().steps;
    const std::uint64_t before = top_sim_counting::heap_allocations();
    const bool ok = sim->advance_to(sim->time() + 1.0);
    const std::uint64_t allocations = top_sim_counting::heap_allocations() - before;
    ASSERT_TRUE(ok) << scene;
    ASSERT_GT(sim->stats().steps - steps_before, 100u) << scene;
    EXPECT_EQ(allocations, 0u) << scene << ": " << allocations << " allocations in "
                               << sim->stats().steps - steps_before << " steps";
  }
}

// implicit_midpoint and fitted_midpoint allocate nothing per step either: their matrices are fixed-size, and their
// Jacobian refreshes and refactorisations (whenever the Newton contraction slows) reuse them.
TEST(Counters, NoHeapAllocationWhileSteppingImplicitMidpoint) {
  for (top_sim::Method method : {top_sim::Method::implicit_midpoint, top_sim::Method::fitted_midpoint}) {
    top_sim::Scene scene = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/frictionless.yaml");
    scene.integrator.method = method;
    scene.integrator.dt = 5e-3;
    top_sim::Simulator sim(scene);
    ASSERT_TRUE(sim.advance_to(0.1));  // past the first steps
    const std::uint64_t steps_before = sim.stats().steps;
    const std::uint64_t before = top_sim_counting::heap_allocations();
    const bool ok = sim.advance_to(2.0);
    const std::uint64_t allocations = top_sim_counting::heap_allocations() - before;
    ASSERT_TRUE(ok);
    ASSERT_EQ(sim.fault(), top_sim::ContactFault::none) << sim.fault_message();
    ASSERT_EQ(sim.stats().steps - steps_before, 380u);
    EXPECT_EQ(allocations, 0u) << top_sim::to_string(method) << ": " << allocations << " allocations in 380 steps";
  }
}

// Advancing builds no sample: with no reader, 1000 advances of 1 ms (10 regime cadence points) make no sample
// analysis and no stationary solve (the cadence classifies with the model's stationary answer, solved at reset and
// at commands only). The first read analyses once, a second read of the same state reuses it, and the next advance
// discards it.
TEST(Counters, NoSampleWithoutAReader) {
  for (const char* scene : {"default.yaml", "hopping.yaml"}) {
    std::unique_ptr<top_sim::Simulator> sim(warmed(scene));
    top_sim::WorkCounters& counters = top_sim::work_counters();
    const double t0 = sim->time(), dt = top_sim::Simulator::kRegimeCadence;
    const std::uint64_t analyses0 = counters.sample_analyses, solves0 = counters.stationary_solves;
    const auto seconds0 = sim->regime_seconds();
    for (int k = 1; k <= 1000; ++k) ASSERT_TRUE(sim->advance_to(t0 + 1e-3 * k)) << scene;
    // Cadence points t_origin + j dt in (t0, t0 + 1 s]: t_origin is 0 (no reset since construction).
    std::uint64_t crossed = 0;
    for (int j = 1; j * dt <= sim->time(); ++j) crossed += j * dt > t0 ? 1 : 0;
    ASSERT_EQ(crossed, 10u) << scene;
    double classified = 0.0;  // the cadence did run: the regime seconds moved on by the second advanced
    for (int r = 0; r < top_sim::kRegimeCount; ++r) classified += sim->regime_seconds()[r] - seconds0[r];
    EXPECT_NEAR(classified, 1.0, 1e-9) << scene;
    EXPECT_EQ(counters.sample_analyses - analyses0, 0u) << scene;
    EXPECT_EQ(counters.stationary_solves - solves0, 0u) << scene;
    const std::uint64_t analyses1 = counters.sample_analyses;
    const top_sim::Snapshot first = sim->snapshot();
    const top_sim::Snapshot second = sim->snapshot();
    const bool exists = sim->stationary().exists;
    EXPECT_EQ(counters.sample_analyses - analyses1, 1u) << scene << ": a read analyses once, then caches";
    EXPECT_EQ(exists && sim->stationary().phi_defined, first.has_stationary_state) << scene;
    EXPECT_EQ(first.energy, second.energy);
    ASSERT_TRUE(sim->advance_to(sim->time() + 1e-4));
    const std::uint64_t analyses2 = counters.sample_analyses;  // after any cadence point the advance crossed
    EXPECT_NE(sim->snapshot().t, first.t);
    EXPECT_EQ(counters.sample_analyses - analyses2, 1u) << scene << ": an advance invalidates the cached sample";
  }
}
