// Issue 11: inputs that used to hang, abort or give a silent wrong answer (each test failed before its fix).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../../src/output/run.hpp"
#include "top_sim/command.hpp"
#include "top_sim/format.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/limits.hpp"

#include "test_util.hpp"

namespace {

using namespace top_sim;
using top_sim_test::scene_from;

std::string scene_text(const std::string& top, const std::string& initial, const std::string& method = "dopri5") {
  return "top: " + top + "\nplane: {inclination: 0.1}\nfriction: pmma\ninitial: " + initial +
         "\nintegrator: {method: " + method + "}\n";
}

const std::string kPointTip =
    "{mass: 0.05, tip_radius: 0.0, com_offset: 0.01, inertia_axial: 1.0e-5, inertia_transverse: 2.0e-5}";

// A point tip (R = 0) never rolls: slip is near 1 as v_t -> 0, a friction kink the explicit method crawled
// through at ~1e-9 s steps (7.5 million steps for 0.01 s). The kink is a stiff layer: rosenbrock4 crosses it.
TEST(Reliability, PointTipRunsOneSecondInFewSteps) {
  Simulator sim(scene_from(scene_text(kPointTip, "{tilt: 0.1, spin: 200.0}")));
  sim.advance_to(1.0);
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_EQ(sim.time(), 1.0);
  EXPECT_GT(sim.layer_steps(), 0u);
  EXPECT_LT(sim.stats().steps, 100000u);  // 807 measured; the crawl needed ~1e9
  EXPECT_LT(sim.max_energy_residual(), 1e-8);
}

// A stationary start with spin 0 is a top at rest on its tip (no rolling): same kink, same cure. It then
// falls like an inverted pendulum: energy is conserved while it does.
TEST(Reliability, StationaryStartWithoutSpinRunsAndConservesEnergy) {
  Simulator sim(scene_from(scene_text("aluminium", "{start: stationary, spin: 0.0}")));
  sim.advance_to(1.0);
  EXPECT_EQ(sim.time(), 1.0);
  EXPECT_LT(sim.stats().steps, 100000u);  // 488 measured; 1.3 million per millisecond before
  EXPECT_LT(sim.max_energy_residual(), 1e-8);
}

TEST(Reliability, InitialStateWithInfiniteEnergyIsABadScene) {
  try {
    scene_from(scene_text("aluminium", "{tilt: 0.1, spin: 200.0, velocity: [1.0e308, 0.0]}"));
    ADD_FAILURE() << "velocity 1e308 accepted (it ran to exit 0 with a NaN energy)";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("initial: the initial energy is inf J"), std::string::npos) << e.what();
  }
}

// A spin of 1e308 was accepted, overflowed the energy and left the node silent: spins are limited to kMaxSpin, in
// scenes and in commands alike, and a refused command leaves the state untouched.
TEST(Reliability, SpinsBeyondTheLimitAreRefused) {
  Simulator sim(scene_from(scene_text("aluminium", "{tilt: 0.1, spin: 200.0}")));
  sim.advance_to(0.1);
  const StateVector before = sim.state();
  for (double spin : {1.0e308, -2.0e6, 1.0e200}) {
    Command spin_up;
    spin_up.spin = spin;
    const std::string error = sim.submit(spin_up);
    EXPECT_NE(error.find("spin = " + format_number(spin) + ": must be finite with |spin| <= 1e+06"), std::string::npos)
        << error;
  }
  sim.advance_to(0.1);
  EXPECT_EQ(sim.state(), before);
  Command at_limit;
  at_limit.spin = kMaxSpin;
  EXPECT_EQ(sim.submit(at_limit), "");
  EXPECT_THROW(scene_from(scene_text("aluminium", "{tilt: 0.1, angular_velocity_transverse: [0.0, 1.0e120]}")),
               SceneError);  // overflowed the regime indicators at t = 0 (found by fuzz_step)
  try {
    scene_from(scene_text("aluminium", "{tilt: 0.1, spin: 1.5e6}"));
    ADD_FAILURE() << "initial.spin 1.5e6 accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("initial.spin: 1500000 is out of range; must be in [-1e+06, 1e+06]"),
              std::string::npos) << e.what();
  }
}

// An unstable fixed step invents energy; its lift-offs and falls were reported as physics (euler dt 0.01: "fallen";
// semi-implicit Euler dt 1e-3 on the hopping top: exit 0 with a residual of 433). It is a numerical fault now,
// stopped at the last step whose energy balance held, with a finite snapshot.
std::string unstable_scene(const std::string& contact, const std::string& spin, const std::string& integrator) {
  return "top: aluminium\nplane: {inclination: 0.1}\nfriction: pmma\ncontact: " + contact +
         "\ninitial: {start: tilted, tilt: 0.1, spin: " + spin + "}\nintegrator: " + integrator + "\n";
}

TEST(Reliability, UnstableFixedStepIsANumericalFault) {
  for (const std::string& text : {unstable_scene("{}", "200.0", "{method: euler, dt: 0.01}"),
                                  unstable_scene("{restitution: 0.5}", "5000.0", "{method: semi_implicit_euler, dt: 1.0e-3}"),
                                  unstable_scene("{restitution: 0.5}", "5000.0", "{method: rk4, dt: 0.01}")}) {
    Simulator sim(scene_from(text));
    sim.advance_to(0.5);
    EXPECT_EQ(sim.fault(), ContactFault::numerical) << text << sim.fault_message();
    EXPECT_NE(sim.fault_message().find("the energy balance drifted by"), std::string::npos) << sim.fault_message();
    const Snapshot s = sim.snapshot();
    EXPECT_TRUE(all_finite(s)) << text;
    EXPECT_LE(s.energy_balance_residual, kDefaultMaxEnergyResidual) << text;
    EXPECT_EQ(s.regime, Regime::contact_fault);
  }
}

// The bound is a scene key: who studies the unstable regime on purpose raises it, and gets the old behaviour.
TEST(Reliability, EnergyResidualBoundIsASceneKey) {
  Simulator sim(scene_from(
      unstable_scene("{}", "200.0", "{method: euler, dt: 0.01, max_energy_residual: 1.0e300}")));
  sim.advance_to(0.5);
  EXPECT_EQ(sim.end_state(), EndState::fallen) << sim.fault_message();
  EXPECT_GT(sim.max_energy_residual(), 1.0);
  EXPECT_THROW(scene_from(unstable_scene("{}", "200.0", "{method: euler, max_energy_residual: 0}")), SceneError);
}

// A stopped run (a fault or an end) no longer moves: a command would be queued and never applied, so it is refused
// with the reason; after a reset the same command is accepted again.
TEST(Reliability, StoppedRunRefusesCommandsUntilReset) {
  Simulator faulted(scene_from(unstable_scene("{}", "200.0", "{method: euler, dt: 0.01}")));
  Simulator ended(scene_from(
      unstable_scene("{}", "200.0", "{method: euler, dt: 0.01, max_energy_residual: 1.0e300}")));
  Command spin;
  spin.spin = 300.0;
  for (Simulator* sim : {&faulted, &ended}) {
    sim->advance_to(0.5);
    ASSERT_TRUE(sim->stopped());
    const double t = sim->time();
    const std::string why = sim->submit(spin);
    const std::string stop = sim == &faulted ? "contact fault numerical" : "end state fallen";
    EXPECT_NE(why.find(stop), std::string::npos) << why;
    EXPECT_NE(why.find("reset it before commanding it"), std::string::npos) << why;
    sim->advance_to(1.0);
    EXPECT_EQ(sim->time(), t);
    sim->reset();
    EXPECT_EQ(sim->submit(spin), "");
  }
}

}  // namespace

namespace {

// dt 1e-300 (fixed step) never advanced t: refused with the floor named.
TEST(Reliability, StepsBelowTheFloorAreABadScene) {
  for (const char* key : {"dt", "max_dt"}) {
    try {
      scene_from("top: aluminium\nfriction: pmma\nintegrator: {method: rk4, " + std::string(key) + ": 1.0e-300}\n");
      ADD_FAILURE() << key << " 1e-300 accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("integrator." + std::string(key) + ": 1e-300 is out of range"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("1e-12"), std::string::npos) << e.what();
    }
  }
}

// Long runs report progress while they advance (top_sim_run prints it on a terminal or with --progress).
TEST(Reliability, RunReportsProgressInWallClockSlices) {
  Simulator sim(scene_from("top: aluminium\nfriction: pmma\n"));
  RunOptions opt;
  opt.duration = 300.0;
  opt.progress_interval = 1e-4;  // [s] wall: a 300 s run takes ~25 ms, so many reports
  std::vector<double> reported;
  opt.on_progress = [&reported](double t) { reported.push_back(t); };
  const RunResult r = run(sim, opt);
  ASSERT_GE(reported.size(), 2u);
  for (std::size_t i = 1; i < reported.size(); ++i) EXPECT_GT(reported[i], reported[i - 1]);
  EXPECT_LT(reported.back(), 300.0);
  EXPECT_EQ(r.sim_seconds, 300.0);  // slicing changes nothing in the result
}

}  // namespace

// A NaN reads "nan" in every message, never "-nan" (a negative NaN is what 0 * inf and friends often give).
TEST(Messages, NaNIsNamedWithoutASign) {
  const double negative_nan = -std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(std::signbit(negative_nan));
  EXPECT_EQ(format_number(negative_nan), "nan");
  Command c;
  c.inclination = negative_nan;
  const std::string error = validate(c, Model());
  EXPECT_NE(error.find("inclination = nan: must be"), std::string::npos) << error;
  EXPECT_EQ(error.find("-nan"), std::string::npos) << error;
  FrictionLaw law;
  law.kind = FrictionLawKind::coulomb;
  law.mu = negative_nan;
  EXPECT_NE(validate(law).find(" = nan: must be"), std::string::npos) << validate(law);
}
