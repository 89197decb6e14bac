// The reduced model on a finite contact (physics.md section 12.1, issue 35): the sleeping state under the patch
// law, the spin-down by drilling and air, model.kind auto on a patch, and the patch's critical inclination.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.hpp"
#include "top_sim/adiabatic.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace {

using namespace top_sim;
using namespace top_sim_test;

// The aluminium top on PMMA (config/) at alpha, with `contact` and `extra`, started asleep or tilted.
std::string patch_scene(double alpha, const std::string& kind, const std::string& contact, const std::string& start,
                        const std::string& extra = "") {
  return "top: aluminium\n"
         "plane: {inclination: " + num(alpha) + "}\n"
         "friction: pmma\n"
         "contact: {" + contact + "}\n"
         "model: {kind: " + kind + "}\n"
         "initial: {" + start + "}\n"
         "integrator: {method: dopri5, dt: 1.0e-4, rtol: 1.0e-8, atol: 1.0e-10}\n" + extra;
}

const char* kAsleep = "start: stationary, spin: 200.0";

// From a sleeping start the full model keeps the patch's sleeping state (tilted by the drilling torque) and spins
// down at its rate; the reduced model follows it. Measured over 200 s: phi 4e-9 rad apart (Hertz, exact), the spin
// decay 2e-8 of itself, f_hat 1e-9 rad, where the point contact's f_hat* is 4e-5 rad off.
TEST(AutoPatch, ReducedModelFollowsTheFullModelFromASleepingStart) {
  for (const char* contact :
       {"patch_radius: hertz", "patch_radius: 1.0e-4", "patch_radius: hertz, drilling_law: elliptic"}) {
    Simulator full(scene_from(patch_scene(0.1, "full", contact, kAsleep)));
    Simulator reduced(scene_from(patch_scene(0.1, "adiabatic", contact, kAsleep)));
    ASSERT_EQ(reduced.model().kind, ModelKind::adiabatic);
    ASSERT_TRUE(full.advance_to(200.0)) << full.fault_message();
    ASSERT_TRUE(reduced.advance_to(200.0)) << reduced.fault_message();
    const Snapshot f = full.snapshot(), r = reduced.snapshot();
    const double decay = 200.0 - f.spin;
    EXPECT_GT(decay, 1.0) << contact;  // the patch spins the top down
    EXPECT_NEAR(r.spin, f.spin, 1e-5 * decay) << contact;
    EXPECT_NEAR(r.phi, f.phi, 1e-7) << contact;
    EXPECT_NEAR(r.phi, r.phi_star, 1e-12) << contact;
    EXPECT_NEAR(angle_between(r.figure_axis, f.figure_axis), 0.0, 1e-7) << contact;
    EXPECT_NEAR(r.drilling_torque, f.drilling_torque, 1e-4 * std::abs(f.drilling_torque)) << contact;
    EXPECT_NEAR(r.patch_radius, f.patch_radius, 1e-6 * f.patch_radius) << contact;
    EXPECT_NEAR(r.mu, f.mu, 1e-6) << contact;
    // The reduced snapshot's friction force and acceleration are the spinning-down state's, not the point
    // contact's: the drift slows with the spin (u' = u_1 spin'). Measured: a_cm 3e-10 m/s^2 apart of 1e-5 to
    // 5e-5, F_t 1e-11 N apart; the point contact's a_cm = 0 would be off by all of it, F_t by m |a_cm| ~ 1e-7 N.
    const double a_full = f.com_acceleration.norm();
    EXPECT_GT(a_full, 1e-6) << contact;
    EXPECT_LT((r.com_acceleration - f.com_acceleration).norm(), 1e-2 * a_full) << contact;
    EXPECT_LT((r.friction_force - f.friction_force).norm(), 1e-2 * full.model().top.mass * a_full) << contact;
    // The drilling torque tilts f_hat* off the point contact's (derivation in physics.md section 12.1).
    Model point = full.model();
    point.finite_contact = FiniteContact{};
    const double tilt = angle_between(f.figure_axis, stationary_state(point, f.spin).f_hat);
    EXPECT_GT(tilt, 100.0 * angle_between(r.figure_axis, f.figure_axis)) << contact;
    EXPECT_LT(full.max_energy_residual(), 1e-9) << contact;
    EXPECT_LT(reduced.max_energy_residual(), 1e-12) << contact;
    note(std::string(contact) + ": phi reduced - full [rad]", r.phi - f.phi);
    note(std::string(contact) + ": spin reduced - full [rad/s], of a decay of", r.spin - f.spin);
    note("  decay [rad/s]", decay);
    note("  f_hat* off the point contact's [rad]", tilt);
  }
}

// physics.md section 12: an upright top pivoting in place loses spin at mu m g Rbar / I_f; with air spin drag k the
// spin solves I_f w' = -mu m g Rbar - k w. The reduced model on a level plane is that top.
TEST(AutoPatch, UprightPivotingTopSpinsDownAtTheClosedFormRate) {
  const double a = 2.0e-4, k = 1.0e-8, mu = 0.3, t = 20.0, w0 = 100.0;
  for (const char* law : {"exact", "elliptic"}) {
    const std::string yaml = "top: aluminium\nplane: {inclination: 0.0}\nfriction: {law: coulomb, mu: 0.3}\n"
                             "model: {kind: adiabatic}\ncontact: {patch_radius: " + num(a) + ", drilling_law: " +
                             law + "}\ninitial: {start: stationary, spin: " + num(w0) + "}\n";
    for (double drag : {0.0, k}) {
      Scene scene = scene_from(yaml + "air: {spin_drag: " + num(drag) + "}\n");
      const Top& top = scene.model.top;
      const double torque = mu * top.mass * scene.model.plane.gravity * 3.0 * M_PI * a / 16.0;
      Simulator sim(scene);
      ASSERT_TRUE(sim.advance_to(t)) << sim.fault_message();
      const double I = top.inertia_axial;
      const double expected = drag == 0.0 ? w0 - torque / I * t
                                          : (w0 + torque / drag) * std::exp(-drag * t / I) - torque / drag;
      EXPECT_NEAR(sim.snapshot().spin, expected, 1e-9 * w0) << law << " k = " << drag;
      EXPECT_NEAR(sim.snapshot().drilling_torque, -torque, 1e-12) << law;
      EXPECT_LT(sim.max_energy_residual(), 1e-10) << law;  // measured 2.5e-12: rounding over 20 s
    }
  }
}

// model.kind auto on a Hertz patch: the full model until the top sleeps, then the reduced model spinning down; over
// 600 s it keeps the full model's contact point within model.auto_tolerance (1e-5 m) and its phi and spin.
TEST(AutoPatch, AutoHandsOverOnAHertzPatchAndKeepsTheFullModelsPath) {
  const std::string start = "start: tilted, tilt: 0.1, spin: 200.0";
  Simulator full(scene_from(patch_scene(0.1, "full", "patch_radius: hertz", start)));
  Simulator automatic(scene_from(patch_scene(0.1, "auto", "patch_radius: hertz", start)));
  for (double t : {300.0, 600.0}) {
    ASSERT_TRUE(full.advance_to(t)) << full.fault_message();
    ASSERT_TRUE(automatic.advance_to(t)) << automatic.fault_message();
    ASSERT_EQ(automatic.model().kind, ModelKind::adiabatic) << "t = " << t;
    const Snapshot f = full.snapshot(), a = automatic.snapshot();
    const double distance = (a.contact_point - f.contact_point).norm();
    EXPECT_LT(distance, 1e-5) << "t = " << t;
    // At 300 s the full model still precesses (phi 1.1e-4 rad off phi*, within the contact point's tolerance).
    if (t == 600.0) {
      EXPECT_NEAR(a.phi, f.phi, 1e-6);
    }
    EXPECT_NEAR(a.spin, f.spin, 1e-6 * std::abs(f.spin)) << "t = " << t;
    note("auto vs full on a Hertz patch, phi at " + std::to_string(t) + " s [rad]", a.phi - f.phi);
    note("auto vs full on a Hertz patch, spin at " + std::to_string(t) + " s [rad/s]", a.spin - f.spin);
    note("auto vs full on a Hertz patch, contact point at " + std::to_string(t) + " s [m]", distance);
  }
  EXPECT_EQ(automatic.handovers(), 1u);
  EXPECT_GT(automatic.reduced_seconds(), 300.0);
  EXPECT_LT(automatic.max_energy_residual(), 1e-9);
  EXPECT_LT(full.snapshot().spin, 190.0);  // it did spin down
}

// A sleeping top on an elliptic-law Hertz patch spins down past the critical spin of its sleeping state (46 rad/s,
// top_sim_stability --sweep-spin) and wakes: auto analyses the reduction along each reduced step, resumes the full
// model where it turns unstable, and the top falls when the full model's does (measured 2537.00 s against 2540.59 s).
TEST(AutoPatch, AutoResumesTheFullModelWhereTheSpinningDownTopWakes) {
  const std::string contact = "patch_radius: hertz, drilling_law: elliptic";
  const std::string start = "start: tilted, tilt: 0.1, spin: 200.0";
  Simulator full(scene_from(patch_scene(0.1, "full", contact, start)));
  Simulator automatic(scene_from(patch_scene(0.1, "auto", contact, start)));
  full.advance_to(3000.0);
  automatic.advance_to(3000.0);
  ASSERT_EQ(full.end_state(), EndState::fallen);
  ASSERT_EQ(automatic.end_state(), EndState::fallen);
  EXPECT_EQ(automatic.handovers(), 1u);
  EXPECT_GT(automatic.reduced_seconds(), 2000.0);
  // Under auto the instability grows from the reduced state's rounding noise, so the fall moves with the rounding:
  // a change of the finite contact's arithmetic (no physics) moved the full model's fall by 0.24 s and auto's by
  // 3.6 s (2540.59 -> 2537.00 s); 10 s (0.4 % of the run) leaves room for that, not for a wake at another spin.
  EXPECT_NEAR(automatic.snapshot().t, full.snapshot().t, 10.0);
  note("fall under auto - under full [s]", automatic.snapshot().t - full.snapshot().t);
}

// A patch lowers the critical inclination: the law's force mu(s) k_F v_d / |w| stays below mu(s) while the patch
// pivots. Between the two critical inclinations the point contact sleeps, the patch cannot: the scene refuses the
// reduced model with the reason, and the full model slides away downhill.
TEST(AutoPatch, APatchHasACriticalInclinationOfItsOwn) {
  Scene scene = scene_from(patch_scene(0.1, "full", "patch_radius: 1.0e-3", kAsleep));
  const double alpha_c = critical_inclination(scene.model.friction);
  auto sleeps = [&scene](double alpha) {
    Model m = scene.model;
    m.plane = make_plane(alpha, m.plane.gravity);
    return stationary_state(m, 200.0).exists;
  };
  double lo = 0.0, hi = alpha_c;  // the patch's critical inclination, by bisection
  ASSERT_TRUE(sleeps(lo));
  for (int i = 0; i < 40; ++i) (sleeps(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  note("critical inclination, point contact [rad]", alpha_c);
  note("critical inclination, 1 mm patch [rad]", lo);
  ASSERT_LT(lo, alpha_c - 0.01);
  const double between = 0.5 * (lo + alpha_c);
  Model m = scene.model;
  m.plane = make_plane(between, m.plane.gravity);
  const StationaryState st = stationary_state(m, 200.0);
  EXPECT_FALSE(st.exists);
  EXPECT_NE(st.reason.find("critical inclination with the patch"), std::string::npos) << st.reason;
  m.finite_contact = FiniteContact{};
  EXPECT_TRUE(stationary_state(m, 200.0).exists);  // a point contact sleeps there
  try {
    scene_from(patch_scene(between, "adiabatic", "patch_radius: 1.0e-3", "start: tilted, spin: 200.0"));
    ADD_FAILURE() << "the reduced model was accepted above the patch's critical inclination";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("model.kind"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("critical inclination with the patch"), std::string::npos) << e.what();
  }
  // The full model on that plane: no sleeping state, the top turns downhill (phi towards pi/2).
  Simulator slides(scene_from(patch_scene(between, "auto", "patch_radius: 1.0e-3", "start: tilted, spin: 200.0")));
  ASSERT_TRUE(slides.advance_to(60.0)) << slides.fault_message();
  EXPECT_EQ(slides.handovers(), 0u);
  EXPECT_GT(slides.snapshot().phi, 1.2);
}

// Commands under the reduced model: a patch and spin drag are carried, rolling resistance and drag refused; under
// adiabatic a patch that the inclination's balance cannot hold is refused with the patch's reason.
TEST(AutoPatch, CommandsUnderTheReducedModel) {
  const Scene scene = scene_from(patch_scene(0.2, "adiabatic", "patch_radius: 1.0e-4", kAsleep));
  Command c;
  c.patch_radius = 1.0e-3;  // 0.2 rad is below the 1 mm patch's critical inclination (0.2346 rad)
  c.spin_drag = 1.0e-9;
  EXPECT_EQ(validate(c, scene.model), "");
  Command rolling;
  rolling.rolling_resistance = 1.0e-5;
  EXPECT_NE(validate(rolling, scene.model).find("rolling_resistance = 1e-05: must be 0 with model.kind adiabatic or "
                                                "auto (the reduced model carries a patch and air spin drag"),
            std::string::npos)
      << validate(rolling, scene.model);
  Command steep;
  steep.inclination = 0.24;  // a point contact sleeps here (alpha_c = 0.2450), a 1 mm patch cannot
  steep.patch_radius = 1.0e-3;
  EXPECT_NE(validate(steep, scene.model).find("critical inclination with the patch"), std::string::npos)
      << validate(steep, scene.model);
  steep.patch_radius = 1.0e-4;
  EXPECT_EQ(validate(steep, scene.model), "");
}

}  // namespace
