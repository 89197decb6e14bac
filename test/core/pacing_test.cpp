// Pacer (include/top_sim/pacing.hpp) driven by a fake wall clock and a fake physics of known cost.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "top_sim/pacing.hpp"

namespace {

using top_sim::Pacer;

// A time-driven loop like top_sim_node's: plan, physics within the budget, record, sleep to the next period.
// The fake physics costs `cost` wall seconds per simulated second.
struct FakeLoop {
  Pacer pacer;
  double wall = 100.0;  // any origin
  double sim = 0.0;
  double cost = 0.1;
  double max_target_lead = 0.0;  // largest target - sim seen by plan(), simulated seconds
  double max_budget = 0.0;
  double max_physics_wall = 0.0;  // largest wall time one tick spent in physics

  FakeLoop(double factor, double rate) : pacer(factor, rate, 100.0, 0.0) {}

  void tick() {
    const Pacer::Tick t = pacer.plan(wall, sim);
    max_target_lead = std::max(max_target_lead, t.target - sim);
    max_budget = std::max(max_budget, t.budget);
    // Physics: as far as the budget allows (the real core stops after the step that exhausts it; here exact).
    const double reachable = sim + t.budget / cost;
    const double reached = std::min(t.target, reachable);
    const double used = (reached - sim) * cost;
    max_physics_wall = std::max(max_physics_wall, used);
    sim = reached;
    pacer.record(wall + used, sim);
    wall += 1.0 / pacer.rate();  // the loop sleeps to the next period (physics used at most half of it)
  }
  void run(double seconds) {
    const long n = std::lround(seconds * pacer.rate());
    for (long i = 0; i < n; ++i) tick();
  }
};

TEST(Pacing, SteadyStateAtFactorOneFollowsTheWallClock) {
  FakeLoop loop(1.0, 200.0);
  loop.run(3.0);
  EXPECT_DOUBLE_EQ(loop.pacer.budget(), 0.5 / 200.0);  // half the period
  EXPECT_NEAR(loop.pacer.achieved_factor(), 1.0, 0.01);
  EXPECT_FALSE(loop.pacer.behind());
  EXPECT_EQ(loop.pacer.debt_drops(), 0u);
  EXPECT_LE(loop.max_target_lead, 1.0 / 200.0 + 1e-12);  // one period of simulated time per tick
  EXPECT_NEAR(loop.sim, 3.0 - 1.0 / 200.0, 1e-9);        // the last tick planned one period before the end
  EXPECT_NEAR(loop.pacer.debt(loop.wall, loop.sim), 1.0 / 200.0, 1e-9);
}

TEST(Pacing, FactorTenAdvancesTenTimesTheWallClock) {
  FakeLoop loop(10.0, 100.0);
  loop.cost = 0.01;
  loop.run(2.0);
  EXPECT_NEAR(loop.pacer.achieved_factor(), 10.0, 0.1);
  EXPECT_FALSE(loop.pacer.behind());
  EXPECT_EQ(loop.pacer.debt_drops(), 0u);
}

TEST(Pacing, FactorZeroRunsAsFastAsTheBudgetAllowsAndIsNeverBehind) {
  FakeLoop loop(0.0, 200.0);
  loop.cost = 0.01;  // 100 simulated seconds per wall second of physics
  loop.run(2.0);
  EXPECT_GE(loop.max_target_lead, loop.pacer.options().fast_horizon - 1e-9);  // only the budget limits a tick
  EXPECT_DOUBLE_EQ(loop.max_budget, 0.5 / 200.0);
  // Half of each period in physics: 0.5 / cost = 50 simulated seconds per wall second.
  EXPECT_NEAR(loop.pacer.achieved_factor(), 50.0, 0.5);
  EXPECT_FALSE(loop.pacer.behind());
  EXPECT_EQ(loop.pacer.debt(loop.wall, loop.sim), 0.0);
}

TEST(Pacing, SlowPhysicsFallsBehindWithBoundedDebtAndRecovers) {
  FakeLoop loop(1.0, 200.0);
  loop.run(1.0);
  ASSERT_FALSE(loop.pacer.behind());
  loop.cost = 10.0;  // 10 wall seconds per simulated second: at most 0.5 / 10 = 0.05 of real time
  const double sim0 = loop.sim, wall0 = loop.wall;
  double max_debt = 0.0;
  bool behind_within_1_5_s = false;
  for (int i = 0; i < 5 * 200; ++i) {
    loop.tick();
    max_debt = std::max(max_debt, loop.pacer.debt(loop.wall, loop.sim));
    if (i < 300 && loop.pacer.behind()) behind_within_1_5_s = true;
    EXPECT_LE(loop.max_physics_wall, loop.pacer.budget() + 1e-12);  // never more than the budget per tick
  }
  EXPECT_TRUE(behind_within_1_5_s);
  EXPECT_TRUE(loop.pacer.behind());
  EXPECT_NEAR(loop.pacer.achieved_factor(), 0.05, 0.005);
  EXPECT_NEAR((loop.sim - sim0) / (loop.wall - wall0), 0.05, 0.005);
  // The debt is dropped once it exceeds 0.5 wall seconds: about once per 0.5 / 0.95 s, never a burst.
  EXPECT_LE(max_debt, 0.5 + 2.0 / 200.0);
  EXPECT_GE(loop.pacer.debt_drops(), 8u);
  EXPECT_LE(loop.pacer.debt_drops(), 11u);
  EXPECT_LE(loop.max_target_lead, 0.5 + 2.0 / 200.0);  // a tick never asks for more than the bounded debt

  loop.cost = 0.1;  // cheap again
  bool recovered_within_1_5_s = false;
  for (int i = 0; i < 300; ++i) {
    loop.tick();
    if (!loop.pacer.behind()) recovered_within_1_5_s = true;
  }
  EXPECT_TRUE(recovered_within_1_5_s);
  loop.run(1.0);
  EXPECT_FALSE(loop.pacer.behind());
  EXPECT_NEAR(loop.pacer.achieved_factor(), 1.0, 0.01);
}

TEST(Pacing, BehindHasHysteresis) {
  // 0.96 of real time lies between behind_enter (0.95) and behind_leave (0.98): the state stays as it was.
  const double cost_096 = (0.5 / 200.0) * 200.0 / 0.96;  // budget per second / cost = 0.96
  FakeLoop ok(1.0, 200.0);
  ok.cost = cost_096;
  for (int i = 0; i < 4 * 200; ++i) {
    ok.tick();
    EXPECT_FALSE(ok.pacer.behind()) << "tick " << i << ", achieved " << ok.pacer.achieved_factor();
  }
  EXPECT_NEAR(ok.pacer.achieved_factor(), 0.96, 0.005);

  FakeLoop slow(1.0, 200.0);
  slow.cost = 10.0;
  slow.run(2.0);
  ASSERT_TRUE(slow.pacer.behind());
  slow.cost = cost_096;
  slow.run(1.0);  // catch-up within the budget is impossible; achieved 0.96 after the window refills
  for (int i = 0; i < 3 * 200; ++i) {
    slow.tick();
    EXPECT_TRUE(slow.pacer.behind()) << "tick " << i << ", achieved " << slow.pacer.achieved_factor();
  }
  EXPECT_NEAR(slow.pacer.achieved_factor(), 0.96, 0.005);
}

TEST(Pacing, NoVerdictBeforeHalfAWindow) {
  FakeLoop loop(1.0, 200.0);
  loop.cost = 10.0;
  for (int i = 0; i < 90; ++i) {  // 0.45 s: the window is too short to judge
    loop.tick();
    EXPECT_FALSE(loop.pacer.behind()) << "tick " << i;
  }
  loop.run(0.2);
  EXPECT_TRUE(loop.pacer.behind());
}

TEST(Pacing, PauseAndResumeReanchorWithoutCatchingUp) {
  FakeLoop loop(1.0, 200.0);
  loop.run(2.0);
  // Pause: the node re-anchors, then records while not running; simulated time stays.
  loop.pacer.reanchor(loop.wall, loop.sim);
  const double sim_paused = loop.sim;
  for (int i = 0; i < 3 * 200; ++i) {
    loop.pacer.record(loop.wall, loop.sim, false);
    loop.wall += 1.0 / 200.0;
    EXPECT_FALSE(loop.pacer.behind());
  }
  EXPECT_EQ(loop.pacer.achieved_factor(), 0.0);
  // Resume: re-anchor; the first tick asks for no more than one period (no burst for the 3 s paused).
  loop.pacer.reanchor(loop.wall, loop.sim);
  const Pacer::Tick t = loop.pacer.plan(loop.wall + 1.0 / 200.0, loop.sim);
  EXPECT_FALSE(t.dropped_debt);
  EXPECT_NEAR(t.target - sim_paused, 1.0 / 200.0, 1e-12);
  loop.run(2.0);
  EXPECT_EQ(loop.pacer.debt_drops(), 0u);
  EXPECT_FALSE(loop.pacer.behind());
  EXPECT_NEAR(loop.pacer.achieved_factor(), 1.0, 0.01);
  EXPECT_NEAR(loop.sim - sim_paused, 2.0, 2.0 / 200.0);
}

// A top stopped by a fault for 3 s, then reset (time keeps running forward: re-anchor without clearing): the run
// that follows is judged on its own seconds, not on the stopped ones (the node once warned "falling behind:
// achieved 0.000223 of requested 1" for a second after such a reset).
TEST(Pacing, ResetAfterAFaultIsNotBehind) {
  FakeLoop loop(1.0, 200.0);
  loop.run(2.0);
  for (int i = 0; i < 3 * 200; ++i) {
    loop.pacer.record(loop.wall, loop.sim, false);
    loop.wall += 1.0 / 200.0;
  }
  loop.pacer.reanchor(loop.wall, loop.sim, false);
  for (int i = 0; i < 2 * 200; ++i) {
    loop.tick();
    EXPECT_FALSE(loop.pacer.behind()) << "tick " << i << " after the reset";
  }
  EXPECT_NEAR(loop.pacer.achieved_factor(), 1.0, 0.01);
}

TEST(Pacing, DebtAboveHalfASecondIsDroppedNotBurst) {
  Pacer p(10.0, 100.0, 0.0, 0.0);
  // 0.3 wall seconds late (3 simulated seconds): kept, the tick tries to catch up within its budget.
  Pacer::Tick t = p.plan(0.3, 0.0);
  EXPECT_FALSE(t.dropped_debt);
  EXPECT_NEAR(t.target, 3.0, 1e-12);
  EXPECT_NEAR(p.debt(0.3, 0.0), 0.3, 1e-12);
  // 2 wall seconds late (the process was starved): dropped; the target is one period ahead.
  t = p.plan(2.0, 0.1);
  EXPECT_TRUE(t.dropped_debt);
  EXPECT_NEAR(t.target, 0.1 + 10.0 / 100.0, 1e-12);
  EXPECT_EQ(p.debt_drops(), 1u);
  EXPECT_NEAR(p.dropped_sim_seconds(), 20.0 - 0.1, 1e-9);
  // The next period asks for one more period.
  t = p.plan(2.01, 0.2);
  EXPECT_FALSE(t.dropped_debt);
  EXPECT_NEAR(t.target, 0.3, 1e-12);
}

TEST(Pacing, SetFactorReanchors) {
  Pacer p(1.0, 100.0, 0.0, 0.0);
  p.record(0.0, 0.0);
  p.record(1.0, 1.0);
  EXPECT_NEAR(p.achieved_factor(), 1.0, 1e-12);
  p.set_real_time_factor(5.0, 1.0, 1.0);
  EXPECT_EQ(p.achieved_factor(), 0.0);
  EXPECT_NEAR(p.plan(1.1, 1.0).target, 1.5, 1e-12);
  p.set_rate(50.0);
  EXPECT_DOUBLE_EQ(p.budget(), 0.5 / 50.0);
}

TEST(Pacing, SampleDrivenDueTimesFollowTheClockAndNeverBurst) {
  // top_sim_run --lcm: samples every 0.01 simulated s at factor 1, sent at their due wall instants.
  Pacer p(1.0, 100.0, 50.0, 0.0);
  double wall = 50.0;
  for (int k = 1; k <= 100; ++k) {
    const double at = p.due(wall, 0.01 * k);
    EXPECT_NEAR(at, 50.0 + 0.01 * k, 1e-9);
    wall = std::max(wall, at) + 1e-4;  // sleep until due, then send
    p.record(wall, 0.01 * k);
  }
  EXPECT_NEAR(p.achieved_factor(), 1.0, 0.01);
  EXPECT_FALSE(p.behind());
  // The physics stalls for 2 s: the next sample is due now, not 2 s ago, and the following ones 0.01 s apart.
  wall += 2.0;
  const double now = wall;
  EXPECT_NEAR(p.due(wall, 1.01), now, 1e-12);
  EXPECT_EQ(p.debt_drops(), 1u);
  EXPECT_NEAR(p.due(wall, 1.02), now + 0.01, 1e-9);
  // A small delay (0.2 s < 0.5 s) is kept: the samples are due in the past and go out at once to catch up.
  wall = now + 0.21;
  EXPECT_NEAR(p.due(wall, 1.02), now + 0.01, 1e-9);
  EXPECT_EQ(p.debt_drops(), 1u);
}

TEST(Pacing, ReportsBehindForSampleDrivenLoopsToo) {
  Pacer p(1.0, 100.0, 0.0, 0.0);
  double wall = 0.0, sim = 0.0;
  for (int k = 0; k < 300; ++k) {  // each sample of 0.01 simulated s takes 0.02 wall s to compute
    sim += 0.01;
    wall = std::max(wall + 0.02, p.due(wall, sim));
    p.record(wall, sim);
  }
  EXPECT_TRUE(p.behind());
  EXPECT_NEAR(p.achieved_factor(), 0.5, 0.01);
}

}  // namespace
