// Scripted events, run-time commands, validation and reset of the Simulator.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

#include "top_sim/simulator.hpp"

namespace top_sim {
namespace {

Scene sleeping_scene(double alpha, double spin) {
  Scene s;
  s.model.plane = make_plane(alpha, 9.81);
  s.initial.start = StartKind::stationary;
  s.initial.spin = spin;
  return s;
}

TEST(SimulatorEvents, InclinationEventAppliesAtItsTimeAndKeepsThePlaneFrameState) {
  Scene scene = sleeping_scene(0.1, 200.0);
  ScriptedEvent e;
  e.t = 1.0;
  e.command.inclination = 0.15;
  scene.events.push_back(e);
  Simulator sim(scene);
  sim.advance_to(1.0 - 1e-9);
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.1);
  const StateVector before = sim.state();
  sim.advance_to(1.0);
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.15);
  // The plane and the top tilt together: the plane-frame state does not jump (1e-9 s of motion apart).
  for (std::size_t i = 0; i < idx::psi; ++i) EXPECT_NEAR(sim.state()[i], before[i], 1e-6) << "component " << i;
}

TEST(SimulatorEvents, AfterAnInclinationChangeTheTopSleepsAtTheNewPhiStar) {
  Scene scene = sleeping_scene(0.1, 200.0);
  ScriptedEvent e;
  e.t = 1.0;
  e.command.inclination = 0.15;
  scene.events.push_back(e);
  Simulator sim(scene);
  sim.advance_to(200.0);
  const Snapshot s = sim.snapshot();
  ASSERT_TRUE(s.has_stationary_state);
  const double expected = stationary_state(sim.model(), 200.0).phi;
  EXPECT_NEAR(s.phi_star, expected, 1e-12);
  // The relaxation to the new sleeping state takes ~100 s at 0.15 rad; 1e-3 rad is the tolerance.
  EXPECT_NEAR(s.phi, expected, 1e-3);
  EXPECT_EQ(s.regime, Regime::sleeping);
}

TEST(SimulatorEvents, SpinReversalCommandMirrorsThePath) {
  Simulator sim(sleeping_scene(0.1, 200.0));
  const double phi_plus = sim.snapshot().phi_star;
  Command c;
  c.spin = -200.0;
  ASSERT_EQ(sim.submit(c), "");
  sim.advance_to(300.0);
  const Snapshot s = sim.snapshot();
  EXPECT_NEAR(s.spin, -200.0, 1.0);  // friction torque trims the spin by well under 1 rad/s
  // physics.md section 5: reversing the spin maps phi* -> pi - phi*.
  EXPECT_NEAR(s.phi_star, M_PI - phi_plus, 1e-12);
  EXPECT_NEAR(s.phi, M_PI - phi_plus, 1e-3);
  // The command re-based the energy balance: what remains is integration error only.
  EXPECT_LT(sim.max_energy_residual(), 1e-8);
}

TEST(SimulatorEvents, InvalidCommandsAreRejectedWithFieldValueAndRangeAndLeaveTheStateAlone) {
  Simulator sim(sleeping_scene(0.1, 200.0));
  sim.advance_to(0.5);
  const StateVector before = sim.state();
  const double t_before = sim.time();
  struct Case {
    Command c;
    std::string field;
  };
  std::vector<Case> cases(6);
  cases[0].c.inclination = std::numeric_limits<double>::quiet_NaN(); cases[0].field = "inclination";
  cases[1].c.inclination = M_PI / 2; cases[1].field = "inclination";
  cases[2].c.spin = std::numeric_limits<double>::infinity(); cases[2].field = "spin";
  cases[3].c.rotor_spin = 100.0; cases[3].field = "rotor_spin";          // this top has no rotor
  cases[4].c.rotor_coupling = -1.0; cases[4].field = "rotor_coupling";
  FrictionChange propelling;
  propelling.kind = FrictionLawKind::coulomb;
  propelling.given.emplace_back(find_friction_parameter("mu"), -0.1);
  cases[5].c.friction = propelling; cases[5].field = "friction.mu";
  for (const auto& k : cases) {
    const std::string error = sim.submit(k.c);
    EXPECT_NE(error.find(k.field), std::string::npos) << error;
  }
  sim.advance_to(0.5);  // nothing pending: nothing changes
  EXPECT_EQ(sim.time(), t_before);
  for (std::size_t i = 0; i < idx::size; ++i) EXPECT_EQ(sim.state()[i], before[i]);
  Command ok;
  ok.inclination = 0.05;
  EXPECT_EQ(sim.submit(ok), "");
}

TEST(SimulatorEvents, NegativeRotorCouplingMessageNamesTheRange) {
  Scene scene = sleeping_scene(0.07, -20.0);
  scene.model.top.has_rotor = true;
  scene.model.top.rotor.inertia_axial = 2e-6;
  scene.model.top.rotor.coupling = 1.5e-9;
  scene.initial.rotor_spin = 2000.0;
  Simulator sim(scene);
  Command c;
  c.rotor_coupling = -2.0;
  const std::string error = sim.submit(c);
  EXPECT_NE(error.find("rotor_coupling = -2"), std::string::npos) << error;
  EXPECT_NE(error.find(">= 0"), std::string::npos) << error;
}

TEST(SimulatorEvents, ResetRestoresTheInitialStateAndTimeKeepsIncreasing) {
  Scene scene = sleeping_scene(0.1, 200.0);
  scene.initial.position = Eigen::Vector2d(0.01, -0.02);
  Simulator sim(scene);
  const StateVector initial = sim.state();
  sim.advance_to(2.0);
  sim.reset();
  EXPECT_DOUBLE_EQ(sim.time(), 2.0);
  for (std::size_t i = 0; i < idx::size; ++i) EXPECT_EQ(sim.state()[i], initial[i]);
  sim.advance_to(3.0);
  EXPECT_DOUBLE_EQ(sim.time(), 3.0);
  EXPECT_GT(sim.state()[idx::x], initial[idx::x]);  // rolling along +h again
}

TEST(SimulatorEvents, EventsAreRelativeToTheLastReset) {
  Scene scene = sleeping_scene(0.1, 200.0);
  ScriptedEvent e;
  e.t = 1.0;
  e.command.inclination = 0.12;
  scene.events.push_back(e);
  Simulator sim(scene);
  sim.advance_to(5.0);
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.12);
  sim.reset();
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.1);
  sim.advance_to(5.5);
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.1);
  sim.advance_to(6.0);
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.12);
}

TEST(SimulatorEvents, AdiabaticModelFollowsTheSleepingStateThroughChanges) {
  Scene scene = sleeping_scene(0.1, 200.0);
  scene.model.kind = ModelKind::adiabatic;
  Simulator sim(scene);
  Command c;
  c.inclination = 0.2;
  ASSERT_EQ(sim.submit(c), "");
  sim.advance_to(1.0);
  const StationaryState st = stationary_state(sim.model(), 200.0);
  // The reduced model is exactly on the sleeping manifold after every change.
  EXPECT_NEAR(sim.snapshot().phi, st.phi, 1e-12);
  EXPECT_NEAR((figure_axis(sim.state()) - st.f_hat).norm(), 0.0, 1e-12);
  Command too_steep;
  too_steep.inclination = 0.3;  // above alpha_c = atan(0.25) = 0.245: the reduced model is invalid
  EXPECT_NE(sim.submit(too_steep).find("adiabatic"), std::string::npos);
}

// The threading contract: another thread submits (validating against the model the owner changes) while the owner
// advances; every accepted command is applied, in order. (Run under -fsanitize=thread to see a race.)
TEST(SimulatorEvents, CommandsSubmittedFromAnotherThreadWhileAdvancingAreAllApplied) {
  Simulator sim(sleeping_scene(0.1, 200.0));
  std::atomic<bool> done{false};
  std::atomic<int> accepted{0};
  std::thread commander([&] {
    for (int i = 1; i <= 200; ++i) {
      Command c;
      c.inclination = 0.1 + 1e-4 * i;
      if (i % 2 == 0) {
        FrictionChange change;  // over the law in force: the core applies it at the step boundary
        change.given.emplace_back(find_friction_parameter("mu_c"), 0.25 + 1e-4 * i);
        c.friction = change;
      }
      if (sim.submit(c).empty()) ++accepted;
      std::this_thread::yield();
    }
    done = true;
  });
  double t = 0.0;
  while (!done) sim.advance_to(t += 1e-3);
  commander.join();
  sim.advance_to(t + 1e-3);  // the last commands take effect
  EXPECT_EQ(accepted, 200);
  EXPECT_DOUBLE_EQ(sim.model().plane.inclination, 0.1 + 1e-4 * 200);
  EXPECT_DOUBLE_EQ(sim.model().friction.mu_c, 0.25 + 1e-4 * 200);
  EXPECT_EQ(sim.fault(), ContactFault::none);
}

}  // namespace
}  // namespace top_sim
