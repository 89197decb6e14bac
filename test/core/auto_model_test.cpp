// model.kind auto (physics.md section 7.1): the full model until the top sleeps, then the reduced model; the
// full model again at commands, scene events and where the reduced model is not valid.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.hpp"
#include "top_sim/adiabatic.hpp"
#include "../../src/core/auto_model.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace {

using namespace top_sim;
using namespace top_sim_test;

// The standard relaxation at alpha, 200 rad/s, under `kind`, with optional extra YAML (events).
Scene relaxation(double alpha, const std::string& kind, const std::string& extra = "") {
  return scene_from(standard_scene(alpha, 200.0, "model: {kind: " + kind + "}\n" + extra));
}

double contact_distance(const Simulator& a, const Simulator& b) {
  return (a.snapshot().contact_point - b.snapshot().contact_point).norm();
}

TEST(AutoModel, HandsOverOnceAsleepAndKeepsTheFullModelsPathOverALongRun) {
  Simulator full(relaxation(0.2, "full")), automatic(relaxation(0.2, "auto"));
  EXPECT_EQ(automatic.model().kind, ModelKind::full);  // it starts in the full model
  for (double t : {300.0, 1000.0}) {
    full.advance_to(t);
    automatic.advance_to(t);
    ASSERT_EQ(automatic.fault(), ContactFault::none) << automatic.fault_message();
    EXPECT_EQ(automatic.model().kind, ModelKind::adiabatic) << "t = " << t;
    const Snapshot s = automatic.snapshot();
    EXPECT_EQ(s.regime, Regime::sleeping);
    // The reduced model sits on the sleeping state: phi is phi* to rounding; the full model's converges to it.
    EXPECT_NEAR(s.phi, s.phi_star, 1e-12);
    EXPECT_NEAR(full.snapshot().phi, s.phi_star, 1e-6) << "t = " << t;
    // The handover's offset is bounded by model.auto_tolerance (1e-5 m); the linear prediction does better.
    EXPECT_LT(contact_distance(full, automatic), 1e-5) << "t = " << t;
    note("auto vs full contact point at " + std::to_string(t) + " s [m]", contact_distance(full, automatic));
  }
  EXPECT_EQ(automatic.handovers(), 1u);
  EXPECT_GT(automatic.reduced_seconds(), 500.0);
  // The energy balance holds across the handover: the decaying modes' energy went to W_diss.
  EXPECT_LT(automatic.max_energy_residual(), 1e-9);
  note("auto reduced seconds of 1000", automatic.reduced_seconds());
}

// The linear prediction of physics.md section 7.1 against the full model itself: from a precessing state, the
// contact point ends up `offset` off the sleeping path through it, travelling at the sleeping velocity of the spin
// it keeps. Measured: the spin it keeps is predicted to 1 % (0.03 % later) of the change still to come; the error
// left grows with the horizon from that residual (0.14 |offset| after 600 s at both starts); without the
// prediction the error is the whole offset, and without the kept spin 100 times more.
TEST(AutoModel, ThePredictedOffsetAndSpinAreWhereTheFullModelGoes) {
  Simulator full(relaxation(0.2, "full"));
  Model reduced = full.model();
  reduced.kind = ModelKind::adiabatic;
  const auto sleeping_velocity = [&reduced](const StateVector& y) {
    StateVector dydt;
    adiabatic_derivative(reduced, y, dydt);
    return Eigen::Vector2d(dydt[idx::x], dydt[idx::x + 1]);
  };
  const auto spin_of = [](const StateVector& y) { return angular_velocity(y).dot(figure_axis(y).normalized()); };
  for (double t0 : {60.0, 100.0}) {
    full.advance_to(t0);
    const Reduction r = analyse_reduction(full.model(), stationary_geometry(full.model()), full.state());
    ASSERT_TRUE(r.valid) << r.reason;
    const Handover h = handover(full.model(), stationary_geometry(full.model()), r, full.state());
    const double t1 = t0 + 600.0;
    Simulator later(relaxation(0.2, "full"));
    later.advance_to(t1);
    const Eigen::Vector2d predicted = position(h.y) + (t1 - t0) * sleeping_velocity(h.y);
    const Eigen::Vector2d uncorrected = position(full.state()) + (t1 - t0) * sleeping_velocity(h.y);
    const double error = (position(later.state()) - predicted).norm();
    const double spin_change = spin_of(later.state()) - spin_of(full.state());
    note("offset predicted at " + std::to_string(t0) + " s [m]", h.offset.norm());
    note("its error 600 s later [m]", error);
    EXPECT_GT(h.offset.norm(), 1e-6);  // a real offset to predict
    EXPECT_LT(error, 0.25 * h.offset.norm());
    EXPECT_LT(error, 0.25 * (position(later.state()) - uncorrected).norm());
    EXPECT_NEAR(spin_of(h.y) - spin_of(full.state()), spin_change, 0.02 * std::abs(spin_change));
  }
}

TEST(AutoModel, AScriptedEventResumesTheFullModelWhichMatchesAPureFullRun) {
  const std::string event = "events:\n  - {t: 400.0, inclination: 0.15}\n";
  Simulator full(relaxation(0.2, "full", event)), automatic(relaxation(0.2, "auto", event));
  full.advance_to(399.0);
  automatic.advance_to(399.0);
  ASSERT_EQ(automatic.model().kind, ModelKind::adiabatic);
  full.advance_to(400.0);
  automatic.advance_to(400.0);
  EXPECT_EQ(automatic.model().kind, ModelKind::full);  // the event landed in the full model
  EXPECT_DOUBLE_EQ(automatic.model().plane.inclination, 0.15);
  // Through the transient the event starts, both models keep the same path.
  for (double t : {401.0, 410.0, 450.0}) {
    full.advance_to(t);
    automatic.advance_to(t);
    EXPECT_EQ(automatic.model().kind, ModelKind::full) << "t = " << t;
    EXPECT_LT(contact_distance(full, automatic), 1e-5) << "t = " << t;
    EXPECT_NEAR(full.snapshot().phi, automatic.snapshot().phi, 1e-4) << "t = " << t;
  }
  // And once asleep at the new inclination it hands over again.
  full.advance_to(2000.0);
  automatic.advance_to(2000.0);
  EXPECT_EQ(automatic.handovers(), 2u);
  EXPECT_EQ(automatic.model().kind, ModelKind::adiabatic);
  EXPECT_LT(contact_distance(full, automatic), 2e-5);
  EXPECT_NEAR(automatic.snapshot().phi, automatic.snapshot().phi_star, 1e-12);
  note("auto vs full contact point 1600 s after the event [m]", contact_distance(full, automatic));
}

TEST(AutoModel, ASpinCommandResumesTheFullModelWhichMatchesAPureFullRun) {
  Simulator full(relaxation(0.2, "full")), automatic(relaxation(0.2, "auto"));
  full.advance_to(500.0);
  automatic.advance_to(500.0);
  ASSERT_EQ(automatic.model().kind, ModelKind::adiabatic);
  Command c;
  c.spin = 150.0;
  ASSERT_EQ(full.submit(c), "");
  ASSERT_EQ(automatic.submit(c), "");
  for (double t : {501.0, 520.0}) {
    full.advance_to(t);
    automatic.advance_to(t);
    EXPECT_EQ(automatic.model().kind, ModelKind::full) << "t = " << t;
    EXPECT_LT(contact_distance(full, automatic), 1e-5) << "t = " << t;
    EXPECT_NEAR(full.snapshot().spin, automatic.snapshot().spin, 1e-6 * 150.0) << "t = " << t;
  }
}

TEST(AutoModel, AnInclinationAboveCriticalResumesTheFullModelAndTheTopSlides) {
  Simulator automatic(relaxation(0.2, "auto"));
  automatic.advance_to(500.0);
  ASSERT_EQ(automatic.model().kind, ModelKind::adiabatic);
  Command c;
  c.inclination = 0.3;  // above alpha_c = atan(0.25) = 0.245: no sleeping state, as for the full model
  ASSERT_EQ(automatic.submit(c), "");
  automatic.advance_to(502.0);
  ASSERT_EQ(automatic.fault(), ContactFault::none) << automatic.fault_message();
  EXPECT_EQ(automatic.model().kind, ModelKind::full);
  const Snapshot s = automatic.snapshot();
  EXPECT_EQ(s.regime, Regime::sliding);
  EXPECT_FALSE(s.has_stationary_state);
  EXPECT_EQ(automatic.handovers(), 1u);  // and it never hands over without a sleeping state
  automatic.advance_to(520.0);
  EXPECT_EQ(automatic.model().kind, ModelKind::full);
  EXPECT_GT(automatic.snapshot().phi, 1.3);  // turning downhill towards pi/2
}

TEST(AutoModel, SnapshotWhileReducedCarriesTheFullModelsFields) {
  Simulator automatic(relaxation(0.2, "auto"));
  Simulator full(relaxation(0.2, "full"));
  automatic.advance_to(800.0);
  full.advance_to(800.0);
  ASSERT_EQ(automatic.model().kind, ModelKind::adiabatic);
  const Snapshot a = automatic.snapshot(), f = full.snapshot();
  EXPECT_EQ(nonfinite_fields(a), "");
  EXPECT_NEAR(a.slip, f.slip, 1e-6);
  EXPECT_NEAR(a.mu, f.mu, 1e-6);
  EXPECT_NEAR(a.normal_force, f.normal_force, 1e-6 * f.normal_force);
  EXPECT_NEAR(angle_between(a.figure_axis, f.figure_axis), 0.0, 1e-6);
  EXPECT_NEAR((a.tip_velocity - f.tip_velocity).norm(), 0.0, 1e-6 * f.tip_velocity.norm());
  EXPECT_NEAR((a.com - f.com).norm(), 0.0, 1e-5);
  EXPECT_NEAR(a.spin, f.spin, 1e-6 * std::abs(f.spin));
}

// The gyroscope-loaded top of gyro_reversal.yaml: its sleeping state at -20 rad/s against a 2000 rad/s rotor is
// unstable (and the bearing drags the shell spin through zero in 20 s, far too fast for the sleeping state to
// follow within auto_tolerance): auto never hands over and runs the full model.
TEST(AutoModel, ABearingThatDragsTheSpinFastKeepsTheFullModelToTheBit) {
  Scene full_scene = load_scene(top_sim_test::scene_path("gyro_reversal"));
  Scene auto_scene = full_scene;
  auto_scene.model.automatic.enabled = true;
  Simulator full(full_scene), automatic(auto_scene);
  const Reduction r = analyse_reduction(automatic.model(), stationary_geometry(automatic.model()), automatic.state());
  EXPECT_FALSE(r.valid);
  EXPECT_FALSE(r.reason.empty());
  for (double t : {10.0, 30.0, 60.0}) {
    full.advance_to(t);
    automatic.advance_to(t);
    EXPECT_EQ(automatic.handovers(), 0u);
    for (std::size_t i = 0; i < automatic.state().size(); ++i) EXPECT_EQ(automatic.state()[i], full.state()[i]) << i;
  }
  // At -200 rad/s the sleeping state is stable, but a rotor 1 rad/s ahead of the shell still drags the path off
  // by more than the tolerance; with the rotor spinning with the shell (no drag) the reduced model takes over.
  auto_scene.initial.spin = -200.0;
  auto_scene.initial.rotor_spin = -199.0;
  const Simulator dragged(auto_scene);
  const Reduction d = analyse_reduction(dragged.model(), stationary_geometry(dragged.model()), dragged.state());
  EXPECT_FALSE(d.valid);
  EXPECT_NE(d.reason.find("bearing"), std::string::npos) << "reason: " << d.reason;
  auto_scene.initial.rotor_spin = -200.0;
  Simulator co_rotating(auto_scene);
  co_rotating.advance_to(1.0);
  EXPECT_EQ(co_rotating.handovers(), 1u);
  EXPECT_EQ(co_rotating.model().kind, ModelKind::adiabatic);
}

TEST(AutoModel, SceneKeysAreCheckedWithClearErrors) {
  EXPECT_TRUE(relaxation(0.1, "auto").model.automatic.enabled);
  EXPECT_FALSE(relaxation(0.1, "full").model.automatic.enabled);
  try {
    scene_from(standard_scene(0.1, 200.0, "model: {kind: full, auto_tolerance: 1e-6}\n"));
    FAIL() << "auto_tolerance without kind auto was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "model.auto_tolerance");
  }
  try {
    scene_from(standard_scene(0.1, 200.0, "model: {kind: auto, auto_tolerance: -1}\n"));
    FAIL() << "a negative auto_tolerance was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "model.auto_tolerance");
    EXPECT_NE(std::string(e.what()).find("> 0"), std::string::npos);
  }
}

}  // namespace
