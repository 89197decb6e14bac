// Findings of the fuzz targets (test/fuzz, docs/reliability.md "Fuzzing"): each test failed before its fix.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "../../src/core/patch_law.hpp"
#include "test_util.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/regime.hpp"

namespace {

using namespace top_sim;
using top_sim_test::scene_from;

// Spin 1e150 has a finite energy (2.5e294 J), so the loader admits it, but |a_cm| and the nutation rate overflow:
// the snapshot held inf with no fault. Any overflow of the sample is a numerical fault, as the energy's was.
// The loader and command validation now refuse spins beyond kMaxSpin; a Scene built in code still reaches the guard.
Scene with_spin(Scene scene, double spin) {
  scene.initial.spin = spin;
  return scene;
}

TEST(FuzzFindings, SpinWhoseDynamicsOverflowIsANumericalFault) {
  EXPECT_THROW(scene_from("top: aluminium\nfriction: pmma\ninitial: {tilt: 0.1, spin: 1.0e150}\n"), SceneError);
  Simulator sim(with_spin(scene_from("top: aluminium\nfriction: pmma\ninitial: {tilt: 0.1}\n"), 1.0e150));
  EXPECT_EQ(sim.fault(), ContactFault::numerical);
  EXPECT_NE(sim.fault_message().find("overflowed"), std::string::npos) << sim.fault_message();
  EXPECT_EQ(sim.snapshot().regime, Regime::contact_fault);
}

// The same as a command (it published inf without a fault): refused now, the state untouched.
TEST(FuzzFindings, CommandedSpinWhoseDynamicsOverflowIsRefused) {
  Simulator sim(scene_from("top: aluminium\nfriction: pmma\n"));
  const StateVector before = sim.state();
  Command spin_up;
  spin_up.spin = 1.0e150;
  EXPECT_NE(sim.submit(spin_up).find("|spin| <= 1e+06"), std::string::npos);
  sim.advance_to(sim.time());
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_EQ(sim.state(), before);
}

}  // namespace

namespace {

using namespace top_sim;
using top_sim_test::scene_from;

// Spin -4.5e129 on a Coulomb plane: after the first slip the steps fell below the resolution of t = 7.3e-16 s and
// advance_to made 358065 steps (4 s) without time moving, until a NaN. A run whose steps stop advancing time is
// stopped with a numerical fault.
TEST(FuzzFindings, StepsThatNoLongerAdvanceTimeAreANumericalFault) {
  const std::string text = "top: aluminium\nfriction: {law: coulomb, mu: 0.3}\ninitial: {start: stationary, spin: ";
  EXPECT_THROW(scene_from(text + "-4.512935414995358e+129}\n"), SceneError);  // beyond kMaxSpin: bad input now
  Scene scene = scene_from(text + "-200.0}\n");
  scene.initial.spin = -4.512935414995358e+129;  // a Scene built in code still reaches the guard
  Simulator sim(scene);
  sim.advance_to(1.0e-3);
  EXPECT_EQ(sim.fault(), ContactFault::numerical) << sim.fault_message();
  EXPECT_NE(sim.fault_message().find("steps too small to change t"), std::string::npos) << sim.fault_message();
  EXPECT_LT(sim.stats().steps, 10000u);
  EXPECT_TRUE(all_finite(sim.state()));
}

}  // namespace

namespace {

using namespace top_sim;

// The hopping top (5000 rad/s) on a plane tilted to just below pi/2 chatters between flight and contact, a switch
// every ~3 ns: advance_to(t, 0 s budget) handled 388796 switches (1.9 s) before returning, because the budget was
// checked only after a step that ended without an event. A handled event is a boundary to return at as well.
TEST(FuzzFindings, BudgetIsKeptWhenEveryStepEndsInAnEvent) {
  Simulator sim(load_scene(top_sim_test::scene_path("hopping")));
  Command wall;
  wall.inclination = std::nextafter(M_PI / 2, 0.0);
  ASSERT_EQ(sim.submit(wall), "");
  for (int call = 0; call < 10 && sim.fault() == ContactFault::none; ++call) {
    const double t = sim.time();
    const std::uint64_t switches = sim.mode_switch_count();
    if (sim.advance_to(1.0e-3, 0.0)) break;
    EXPECT_LE(sim.mode_switch_count() - switches, 1u) << "call " << call;
    EXPECT_GT(sim.time(), t) << "call " << call;
  }
  EXPECT_LT(sim.mode_switch_count(), 20u);
}

}  // namespace

namespace {

using top_sim_test::scene_from;

// A key with a NUL character ("\0" in a double-quoted YAML key) ended up in the message, and what() (a C string)
// stopped there: "fuzz_scene.yaml: " without the problem. Control characters are shown escaped.
TEST(FuzzFindings, SceneErrorShowsNulCharactersEscaped) {
  try {
    scene_from("top: aluminium\n\"a\\0b\": 1\n", "nul.yaml");
    ADD_FAILURE() << "a key with a NUL accepted";
  } catch (const top_sim::SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("a\\x00b: unknown key"), std::string::npos) << message;
  }
}

// Step input with air drag 1.1e163 N s/m (and command's 1e300): the drag tipped the top off the plane, and the
// closed-form flight (physics.md, "F = 0") ignored the air: the top fell freely, 4.9 um into the plane in 1 ms, with no
// fault. Air acts in flight (section 12): such a flight is stepped, and the drag slows it and dissipates.
TEST(FuzzFindings, AirActsInFlight) {
  const std::string top = "top: aluminium\nfriction: pmma\nplane: {inclination: 0.1}\n"
                          "initial: {tilt: 0.1, spin: 200, gap: 0.01, velocity: [1.0, 0.0]}\n";
  Simulator still(scene_from(top)), windy(scene_from(top + "air: {drag: 0.05, spin_drag: 1.0e-6}\n"));
  for (Simulator* sim : {&still, &windy}) {
    ASSERT_TRUE(sim->advance_to(0.01));
    ASSERT_EQ(sim->contact_mode(), ContactMode::flight);  // it falls 0.5 g t^2 = 0.5 mm of its 10 mm
  }
  const Snapshot a = still.snapshot(), b = windy.snapshot();
  EXPECT_EQ(a.dissipated_work, 0.0);
  EXPECT_GT(b.dissipated_work, 0.0);  // exactly 0 before the fix
  EXPECT_LT(b.com_velocity.norm(), a.com_velocity.norm());
  EXPECT_LT(std::abs(b.energy_balance_residual), 1e-6);
}

// Command input with air drag 1e300 N s/m: a_cm of 1e299 m/s^2 is finite, but norm() squared it to inf, so the
// snapshot's acceleration indicator was inf without a fault (the overflow guard runs at regime points only).
TEST(FuzzFindings, IndicatorsOfAFiniteHugeAccelerationAreFinite) {
  const Scene scene = scene_from("top: aluminium\nfriction: pmma\n");
  const StateVector y = initial_state(scene);
  Dynamics dyn;
  evaluate_dynamics(scene.model, ContactMode::slipping, y, dyn);
  dyn.a_cm = Eigen::Vector3d(1e299, -1e299, 0.0);
  const RegimeIndicators ind = regime_indicators(scene.model, ContactMode::slipping, y, dyn, stationary_state(scene.model, 200.0));
  EXPECT_DOUBLE_EQ(ind.acceleration, std::sqrt(2.0) * 1e299);
}

// Command input with a patch radius of 2.8e180 m on the default scene under the auto model: lever * omega_n = 5e182
// m/s squared to inf in the patch law, so the snapshot's slip was inf without a fault at t = 0.1 ms. |w| falls back to
// hypot when the square overflows (bit-identical otherwise); the run now ends in a numerical fault.
TEST(FuzzFindings, PatchOfAHugeRadiusHasAFiniteSlip) {
  const Scene scene = scene_from("top: aluminium\nfriction: pmma\nmodel: {kind: auto}\n");
  const PatchLaw law = patch_law(scene.model, 2.77e180, 1e-3, 200.0, 1e-3);
  EXPECT_NEAR(law.slip, 1.0, 1e-12);
  EXPECT_TRUE(std::isfinite(law.mu) && std::isfinite(law.force_per_speed) && std::isfinite(law.drilling));
  Simulator sim(scene);
  Command c;
  c.patch_radius = 2.7744062535996355e180;  // since bug 10 beyond kMaxPatchRadius: refused, the field and range named
  const std::string why = sim.submit(c);
  EXPECT_NE(why.find("patch_radius"), std::string::npos) << why;
  EXPECT_NE(why.find("in [0, 1] m"), std::string::npos) << why;
}

// Step input (issue 49's run at 39d85a9): the default top with contact.patch_radius 1.8e308 m, the exact drilling law,
// starting 4e-33 m above the plane: at the touchdown the lever Rbar |omega_n| overflowed to inf and the slip was NaN
// one step before the numerical fault. A patch radius beyond kMaxPatchRadius (1 m) is now refused at load.
TEST(FuzzFindings, SceneWithAPatchBeyondTheLimitIsRefused) {
  for (const char* radius : {"1.7976931348623157e+308", "1.5"}) {
    try {
      scene_from(std::string("top: aluminium\nfriction: pmma\ncontact: {patch_radius: ") + radius + "}\n");
      ADD_FAILURE() << radius << " accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("contact.patch_radius"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("in [0, 1] [m]"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(scene_from("top: aluminium\nfriction: pmma\ncontact: {patch_radius: 1.0}\n"));
}

// Step input: the default top made one sphere of radius 1e300 m at offset pi, spin 0: v_t (1.6e297 m/s, the sphere's
// rolling) was finite but norm() squared it to inf, so the slip was inf without a fault at t = 0.1 ms. The contact's
// |v_t| and friction direction no longer overflow (safe_norm, regularized_norm in contact.hpp).
TEST(FuzzFindings, TipSphereOfAHugeRadiusHasAFiniteSlip) {
  Scene scene = scene_from("top: aluminium\nfriction: pmma\n");
  scene.model.top.tip_radius = 1e300;
  const Eigen::Vector3d u(-4.9e-3, -4.9e-3, 0.0), omega(1.6e-3, -1.6e-3, 2e-21);
  const ContactKinematics k = contact_kinematics(scene.model, u, omega);
  EXPECT_TRUE(std::isfinite(k.slip) && k.t_hat.allFinite()) << k.slip;
  EXPECT_NEAR(k.slip, 1.0, 1e-9);
  EXPECT_NEAR(k.t_hat.norm(), 1.0, 1e-12);
}

}  // namespace
