// Deterministic counters that fail when bookkeeping creeps into the hot path (issue 21's guard; timings live in
// bench/, never here): right-hand sides per dopri5 step and heap allocations while stepping. The counting
// operator new below replaces the global one for this whole test binary (it only counts).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "test_util.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {
std::atomic<std::uint64_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

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
TEST(Counters, RightHandSidesPerDopri5Step) {
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

// Stepping allocates nothing: one advance over many steps makes at most the allocations of its one sample at the
// end (the stationary solve's root list for some laws, until samples are lazy).
TEST(Counters, NoHeapAllocationWhileStepping) {
  for (const char* scene : {"default.yaml", "hopping.yaml", "coulomb.yaml"}) {
    std::unique_ptr<top_sim::Simulator> sim(warmed(scene));
    const std::uint64_t steps_before = sim->stats().steps;
    const std::uint64_t before = g_allocations;
    const bool ok = sim->advance_to(sim->time() + 1.0);
    const std::uint64_t allocations = g_allocations - before;
    ASSERT_TRUE(ok) << scene;
    ASSERT_GT(sim->stats().steps - steps_before, 100u) << scene;
    EXPECT_LE(allocations, 1u) << scene << ": " << allocations << " allocations in "
                               << sim->stats().steps - steps_before << " steps";
  }
}
