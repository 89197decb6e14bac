// Extreme inputs, each with its expected outcome (issue 2, item 7; physics.md sections 4 and 5): falls, lift-off,
// upright, very fast, R = 0, no stationary state, Painleve, Coulomb friction, and every fault on the initial state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "test_util.hpp"
#include "top_sim/dynamics.hpp"

namespace {

using namespace top_sim;
using top_sim_test::CheckedRun;
using top_sim_test::run_checked;
using top_sim_test::scene_from;

std::string aluminium_scene(const std::string& plane, const std::string& friction, const std::string& initial,
                            const std::string& extra = "") {
  return "top: aluminium\nplane: " + plane + "\nfriction: " + friction + "\ninitial: " + initial + "\n" + extra;
}

TEST(Extremes, NoSpinFallsOverInAboutAFifthOfASecond) {
  Simulator sim(scene_from(aluminium_scene("{inclination: 0.1}", "pmma", "{tilt: 0.1, spin: 0.0}")));
  const CheckedRun r = run_checked(sim, 2.0, 100.0);
  EXPECT_EQ(r.nonfinite, "");
  ASSERT_EQ(r.result.final.end_state, EndState::fallen) << to_string(r.result.final.fault) << ": "
                                                           << r.result.final.fault_message;
  EXPECT_EQ(r.result.final.fault, ContactFault::none);
  EXPECT_EQ(r.result.final.regime, Regime::fallen);
  EXPECT_NE(r.result.final.end_message.find("fallen"), std::string::npos);
  // Inverted pendulum about the tip: lambda = sqrt(m g f / (I_d + m f^2)) = 21 1/s; from 0.1 rad to 1.2 rad,
  // cosh(lambda t) = 12 gives 0.15 s (reference: about 0.2 s). The band allows for the sliding tip and R.
  EXPECT_GT(r.result.sim_seconds, 0.1);
  EXPECT_LT(r.result.sim_seconds, 0.3);
  // The end is located on the max_tilt boundary (bisection to 1e-12 s; the margin is ~1e-11 there).
  EXPECT_NEAR(r.result.final.figure_axis.z(), std::cos(1.2), 1e-6);
  top_sim_test::note("no spin: fallen at t [s]", r.result.sim_seconds);
}

TEST(Extremes, ExactlyUprightOnAHorizontalPlaneStaysPut) {
  const Scene scene = load_scene(top_sim_test::scene_path("upright"));
  ASSERT_EQ(scene.model.plane.inclination, 0.0);
  Simulator sim(scene);
  const CheckedRun r = run_checked(sim, scene.duration, 10.0);
  EXPECT_EQ(r.nonfinite, "");
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  // An exact equilibrium: no force but N n, no torque; nothing may move (rounding only).
  EXPECT_LT(r.result.final.contact_point.norm(), 1e-12);
  EXPECT_LT(r.result.final.tip_velocity.norm(), 1e-12);
  EXPECT_LT((r.result.final.figure_axis - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(r.result.final.spin, scene.initial.spin, 1e-9);
  EXPECT_EQ(r.result.final.slip, 0.0);  // v_t = 0: the v_eps regularisation removes the 0/0
  // phi* undefined (the top does not move), with the reason.
  EXPECT_FALSE(r.result.phi_star.has_value());
  EXPECT_FALSE(r.result.stationary_note.empty());
}

TEST(Extremes, FiveThousandRadPerSecondStartedAsleepStaysAtPhiStar) {
  const Scene scene =
      scene_from(aluminium_scene("{inclination: 0.1}", "{law: paper, mu_c: 0.25, s_c: 0.6}", "{start: stationary, spin: 5000.0}"));
  Simulator sim(scene);
  const Eigen::Vector3d f_star = stationary_state(scene.model, 5000.0).f_hat;
  const CheckedRun r = run_checked(sim, 10.0, 10.0);
  EXPECT_EQ(r.nonfinite, "");
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_EQ(r.result.final.regime, Regime::sleeping);
  ASSERT_TRUE(r.result.phi_measured.has_value());
  // An equilibrium: only v_eps (~1e-10 rad at this spin) and integration error move it; physics.md reports
  // 1e-7 for a sleeping top, so 1e-6 rad.
  EXPECT_NEAR(*r.result.phi_measured, top_sim_test::paper_phi_star(0.1, 0.25, 0.6), 1e-6);
  EXPECT_LT(top_sim_test::angle_between(r.result.final.figure_axis, f_star), 1e-6);
  top_sim_test::note("5000 rad/s asleep: phi_measured - phi*",
                     *r.result.phi_measured - top_sim_test::paper_phi_star(0.1, 0.25, 0.6));
}

// R = 0: the tip is a point. mu(s) then varies over |u| ~ v_eps (s = |u| / (|u| + v_eps)), a stiff mode of rate
// ~ mu'(0) g / v_eps, so the scene uses the stiff method (with dopri5 it crawls: ~7 s CPU per 10 ms simulated).
TEST(Extremes, ZeroTipRadiusRunsAndReportsPhiStarUndefined) {
  Simulator sim(scene_from("top: {tip_radius: 0.0}\nplane: {inclination: 0.1}\nfriction: pmma\n"
                           "initial: {tilt: 0.1, spin: 200.0}\n"
                           "integrator: {method: rosenbrock4, rtol: 1.0e-6, atol: 1.0e-9}\n"));
  ASSERT_EQ(sim.model().top.tip_radius, 0.0);
  const CheckedRun r = run_checked(sim, 10.0, 10.0);
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_NEAR(r.result.sim_seconds, 10.0, 1e-9);
  EXPECT_FALSE(r.result.phi_star.has_value());
  EXPECT_NE(r.result.stationary_note.find("R = 0"), std::string::npos) << r.result.stationary_note;
  EXPECT_FALSE(r.result.final.has_stationary_state);
  // The summary writes null, not a number, for phi_star.
  const std::string json = summary_json(sim.scene(), r.result);
  EXPECT_NE(json.find("\"phi_star\": null"), std::string::npos) << json;
}

TEST(Extremes, CentreOfMassTooLowForTheInclinationHasNoStationaryState) {
  // R sin(alpha) = 12 mm * sin(0.2) = 2.38 mm > f = 2 mm; tan(0.2) < mu_c, so only the geometry forbids it.
  const Scene scene = scene_from(
      "top: {tip_radius: 0.012, com_offset: 0.002}\nplane: {inclination: 0.2}\nfriction: pmma\n"
      "initial: {tilt: 0.0, spin: 200.0}\n");
  const StationaryState st = stationary_state(scene.model, 200.0);
  EXPECT_FALSE(st.exists);
  EXPECT_NE(st.reason.find("R sin(alpha)"), std::string::npos) << st.reason;
  Simulator sim(scene);
  const CheckedRun r = run_checked(sim, 0.5, 100.0);
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_FALSE(r.result.phi_star.has_value());
  EXPECT_NE(r.result.stationary_note.find("R sin(alpha)"), std::string::npos) << r.result.stationary_note;
  const std::string json = summary_json(sim.scene(), r.result);
  EXPECT_NE(json.find("\"phi_star\": null"), std::string::npos) << json;
  // Loading such a scene with a stationary start is refused, naming why.
  try {
    scene_from("top: {tip_radius: 0.012, com_offset: 0.002}\nplane: {inclination: 0.2}\nfriction: pmma\n"
               "initial: {start: stationary, spin: 200.0}\n",
               "low_com.yaml");
    ADD_FAILURE() << "a stationary start without a stationary state was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("R sin(alpha)"), std::string::npos) << e.what();
  }
}

// ---- Painleve -------------------------------------------------------------------------------------------------

// physics.md section 4 evaluated by hand for f_hat = (sin th, 0, cos th), friction direction t = (cos b, sin b, 0):
// (rho x d) . (f_hat x n) = (rho.f)(d.n) - (rho.n)(d.f) = -f sin^2 th - mu cos b sin th (R + f cos th), and
// (f_hat x n) is perpendicular to f_hat, so A = that / I_d and m (1/m - f A) = 1 + (m f sin th / I_d) *
// (f sin th + mu cos b (R + f cos th)).
double painleve_margin_by_hand(const Top& t, double th, double mu, double b) {
  const double R = t.tip_radius, f = t.com_offset;
  return 1.0 + t.mass * f * std::sin(th) / t.inertia_transverse *
                   (f * std::sin(th) + mu * std::cos(b) * (R + f * std::cos(th)));
}

// The core's margin for a sliding state (spin 0, so v_t = u) on a horizontal plane.
double painleve_margin(const Model& m, double th, double b) {
  StateVector y{};
  set_figure_axis(y, Eigen::Vector3d(std::sin(th), 0.0, std::cos(th)));
  set_velocity(y, Eigen::Vector2d(std::cos(b), std::sin(b)));  // 1 m/s >> v_eps: t_hat is a unit vector
  Dynamics dyn;
  evaluate_dynamics(m, ContactMode::slipping, y, dyn);
  return dyn.margins.painleve;
}

Model coulomb_model(double mu) {
  Model m;  // aluminium top defaults
  m.plane = make_plane(0.0, 9.81);
  m.friction.kind = FrictionLawKind::coulomb;
  m.friction.mu = mu;
  return m;
}

TEST(Painleve, MarginMatchesTheClosedForm) {
  for (double th : {0.1, 0.4, 0.67, 1.1})
    for (double mu : {0.3, 2.0, 4.0})
      for (double b : {0.0, 1.0, 2.5, M_PI}) {
        const Model m = coulomb_model(mu);
        // Terms are O(10); rounding 1e-15 relative.
        EXPECT_NEAR(painleve_margin(m, th, b), painleve_margin_by_hand(m.top, th, mu, b), 1e-12)
            << "theta " << th << ", mu " << mu << ", direction " << b;
      }
}

// Smallest mu giving a Painleve-inconsistent contact anywhere within max_tilt: the margin is linear in mu, so the
// root at the worst direction (b = pi) is margin(0) / (margin(0) - margin(1)); minimised over theta.
TEST(Painleve, SmallestInconsistentFrictionOfTheAluminiumTopIsAbout2p7) {
  const Model m0 = coulomb_model(0.0), m1 = coulomb_model(1.0);
  double mu_min = INFINITY, th_min = 0.0;
  for (double th = 0.01; th <= m0.top.max_tilt + 1e-12; th += 0.001) {
    const double a = painleve_margin(m0, th, M_PI), b = painleve_margin(m1, th, M_PI);
    const double mu = a / (a - b);
    if (mu < mu_min) mu_min = mu, th_min = th;
  }
  // Reference: "Painleve-inconsistent only for mu above about 2.7" (physics.md section 5).
  EXPECT_GT(mu_min, 2.5);
  EXPECT_LT(mu_min, 3.0);
  // Analytic minimum of (I_d / (m f sin th) + f sin th) / (R + f cos th) on the same grid agrees.
  const Top& t = m0.top;
  double mu_formula = INFINITY;
  for (double th = 0.01; th <= t.max_tilt + 1e-12; th += 0.001)
    mu_formula = std::min(mu_formula, (t.inertia_transverse / (t.mass * t.com_offset * std::sin(th)) +
                                       t.com_offset * std::sin(th)) /
                                          (t.tip_radius + t.com_offset * std::cos(th)));
  EXPECT_NEAR(mu_min, mu_formula, 1e-9);
  top_sim_test::note("Painleve: smallest mu", mu_min);
  top_sim_test::note("Painleve: at tilt [rad]", th_min);
}

// A sliding start in the Painleve region: tilt 0.67 rad (near the worst tilt), sliding against the tilt direction.
std::string painleve_scene(double mu) {
  return aluminium_scene("{inclination: 0.0}",
                         "{law: coulomb, mu: " + top_sim_test::num(mu) + ", regularization_speed: 1.0e-6}",
                         "{tilt: 0.67, spin: 0.0, velocity: [-1.0, 0.0]}",
                         "integrator: {method: rosenbrock4, rtol: 1.0e-6, atol: 1.0e-9}\n");
}

TEST(Painleve, FaultOnTheInitialStateAboveTheThreshold) {
  // mu = 3 exceeds the bound at 0.67 rad (2.73): the very first state is inconsistent.
  Simulator sim(scene_from(painleve_scene(3.0)));
  EXPECT_EQ(sim.fault(), ContactFault::painleve) << to_string(sim.fault());
  const Snapshot s = sim.snapshot();
  EXPECT_EQ(s.regime, Regime::contact_fault);
  EXPECT_EQ(top_sim_test::nonfinite_fields(s), "");
  EXPECT_NE(s.fault_message.find("Painleve"), std::string::npos) << s.fault_message;
  sim.advance_to(1.0);
  EXPECT_EQ(sim.time(), 0.0);  // a faulted top does not advance
}

TEST(Painleve, NeverBelowTheSmallestInconsistentFriction) {
  // mu = 2.5 is below the minimum over all tilts and directions (previous test): whatever happens, not Painleve.
  Simulator sim(scene_from(painleve_scene(2.5)));
  const CheckedRun r = run_checked(sim, 1.0, 1000.0);
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_NE(r.result.final.fault, ContactFault::painleve) << r.result.final.fault_message;
}

// The reference's 2.7 is the minimum over all tilts (at 0.67 rad). The standard start never gets there: its tilt
// stays small, where the bound is far higher, so even mu = 3 gives no Painleve fault from it. Checked by tracking
// the largest tilt from the plane normal and evaluating the closed-form bound there.
TEST(Painleve, StandardStartStaysConsistentAtMuThreeBecauseItsTiltStaysSmall) {
  Simulator sim(scene_from(aluminium_scene("{inclination: 0.1}", "{law: coulomb, mu: 3.0, regularization_speed: 1.0e-6}",
                                           "{tilt: 0.1, spin: 200.0}",
                                           "integrator: {method: rosenbrock4, rtol: 1.0e-6, atol: 1.0e-9}\n")));
  double tilt_max = 0.0;
  for (int k = 1; k <= 500; ++k) {
    sim.advance_to(0.01 * k);
    tilt_max = std::max(tilt_max, std::acos(std::min(1.0, sim.snapshot().figure_axis.z())));
  }
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  // The worst-direction bound decreases with the tilt up to 0.67 rad, so below tilt_max it is at least its value there.
  ASSERT_LT(tilt_max, 0.6);
  const Top t = sim.model().top;
  const double bound = (t.inertia_transverse / (t.mass * t.com_offset * std::sin(tilt_max)) +
                        t.com_offset * std::sin(tilt_max)) /
                       (t.tip_radius + t.com_offset * std::cos(tilt_max));
  EXPECT_GT(bound, 3.0);
  top_sim_test::note("standard start, Coulomb mu 3: largest tilt [rad]", tilt_max);
  top_sim_test::note("Painleve bound at that tilt", bound);
}

// ---- faults already present in the initial state --------------------------------------------------------------

TEST(InitialFaults, TiltBeyondMaxTiltIsABadScene) {
  try {
    scene_from(aluminium_scene("{inclination: 0.0}", "pmma", "{tilt: 1.3, spin: 200.0}"));
    ADD_FAILURE() << "a top tilted beyond max_tilt accepted";
  } catch (const SceneError& e) {  // issue 11: bad input (exit 2), not a contact fault at t = 0 (exit 3)
    EXPECT_NE(std::string(e.what()).find("initial.tilt: the figure axis starts 1.3 rad from the plane normal; "
                                         "must be < top.max_tilt = 1.2 rad"),
              std::string::npos)
        << e.what();
  }
}

// A Scene built in code (not through the loader) can still start fallen: the Simulator says so at t = 0.
TEST(InitialFaults, TiltBeyondMaxTiltIsFallenAtTimeZero) {
  Scene scene = scene_from(aluminium_scene("{inclination: 0.0}", "pmma", "{tilt: 0.1, spin: 200.0}"));
  scene.initial.tilt = 1.3;
  Simulator sim(scene);
  EXPECT_EQ(sim.end_state(), EndState::fallen) << to_string(sim.fault());
  EXPECT_EQ(sim.fault(), ContactFault::none);
  const Snapshot s = sim.snapshot();
  EXPECT_EQ(s.regime, Regime::fallen);
  EXPECT_EQ(top_sim_test::nonfinite_fields(s), "");
  RunOptions opt;
  opt.duration = 1.0;
  const RunResult r = run(sim, opt);
  EXPECT_EQ(r.sim_seconds, 0.0);
  EXPECT_NE(summary_json(sim.scene(), r).find("\"end_state_message\": \"t = 0 s: end state fallen"), std::string::npos)
      << summary_json(sim.scene(), r);
}

TEST(InitialModes, HugeTransverseAngularVelocityStartsInFlight) {
  // omega_t = 100 rad/s perpendicular to f_hat: the centripetal term f |omega_t|^2 cos(th) ~ 95 m/s^2 > g, so the
  // slipping N < 0 and the closing rule of physics.md section 9 starts the top in flight (no fault).
  const Scene scene = scene_from(aluminium_scene("{inclination: 0.1}", "pmma",
                                                 "{tilt: 0.3, spin: 200.0, angular_velocity_transverse: [0.0, 100.0]}"));
  Dynamics dyn;
  evaluate_dynamics(scene.model, ContactMode::slipping, initial_state(scene), dyn);
  EXPECT_LT(dyn.normal_force, 0.0);
  Simulator sim(scene);
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_EQ(sim.contact_mode(), ContactMode::flight);
  sim.advance_to(0.05);
  EXPECT_EQ(top_sim_test::nonfinite_fields(sim.snapshot()), "");
  EXPECT_GE(sim.mode_switch_count(), 1u);  // it lands
}

TEST(InitialFaults, HugeFrictionIsPainleveAtTimeZeroFromTheStandardTilt) {
  // At 0.1 rad the bound for the worst direction is (I_d/(m f sin th) + f sin th)/(R + f cos th) = 10.5; the
  // standard start slides sideways (v_t = -R omega x n, along -y), so choose a start sliding against the tilt.
  const Scene scene = scene_from(aluminium_scene("{inclination: 0.0}", "{law: coulomb, mu: 20.0}",
                                                 "{tilt: 0.1, spin: 0.0, velocity: [-0.5, 0.0]}"));
  Simulator sim(scene);
  EXPECT_EQ(sim.fault(), ContactFault::painleve) << to_string(sim.fault());
  EXPECT_EQ(top_sim_test::nonfinite_fields(sim.snapshot()), "");
}

// ---- Coulomb friction (mu(0) > 0: stiff, physics.md section 5) --------------------------------------------------

TEST(Coulomb, FiveSecondsWithTheStiffMethodFinishWithTheEnergyBalanceHeld) {
  // v_eps = 1e-6 m/s: one of physics.md's documented remedies for the stick stiffness (rate mu g / v_eps).
  Simulator sim(scene_from(aluminium_scene("{inclination: 0.1}", "{law: coulomb, mu: 0.3, regularization_speed: 1.0e-6}",
                                           "{tilt: 0.1, spin: 200.0}",
                                           "integrator: {method: rosenbrock4, rtol: 1.0e-6, atol: 1.0e-9}\n")));
  const CheckedRun r = run_checked(sim, 5.0, 20.0);
  EXPECT_EQ(r.nonfinite, "");
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_NEAR(r.result.sim_seconds, 5.0, 1e-9);
  // At rtol 1e-6 the balance drifts by O(rtol) per nutation period; 1e-5 relative over the run.
  EXPECT_LT(r.result.max_energy_residual, 1e-5);
  EXPECT_GT(r.result.final.dissipated_work, 0.0);  // friction did work, so the balance is not trivially 0
  top_sim_test::note("Coulomb v_eps 1e-6, 5 s rosenbrock4: steps", static_cast<double>(r.result.stats.steps));
  top_sim_test::note("Coulomb v_eps 1e-6, 5 s rosenbrock4: energy residual", r.result.max_energy_residual);
}

// Was DISABLED before the stick model (rosenbrock4 took 2.5e6 steps for 0.1 s at v_eps = 1e-9 while the top
// stuck and slipped inside the regularised layer); with the rolling mode of physics.md section 9 it finishes.
TEST(Coulomb, DefaultRegularizationWithTheStiffMethodTakesBoundedSteps) {
  Simulator sim(scene_from(aluminium_scene("{inclination: 0.1}", "{law: coulomb, mu: 0.3, regularization_speed: 1.0e-9}",
                                           "{tilt: 0.1, spin: 200.0}",
                                           "integrator: {method: rosenbrock4, rtol: 1.0e-6, atol: 1.0e-9}\n")));
  const std::uint64_t budget = 100000;
  for (int k = 1; k <= 5000 && sim.stats().steps < budget && sim.fault() == ContactFault::none; ++k)
    sim.advance_to(1e-3 * k);
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_NEAR(sim.time(), 5.0, 1e-9) << "stopped after " << sim.stats().steps << " steps at t = " << sim.time()
                                     << " s";
  EXPECT_EQ(top_sim_test::nonfinite_fields(sim.snapshot()), "");
  top_sim_test::note("Coulomb v_eps 1e-9 rosenbrock4: simulated seconds within the step budget", sim.time());
}

}  // namespace
