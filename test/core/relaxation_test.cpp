// Relaxation to the sleeping state (physics.md section 5, observable consequences 1 and 2): from the standard
// tilted start the top nutates, precesses and falls asleep travelling at the analytic phi*.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_util.hpp"

namespace {

using namespace top_sim;
using top_sim_test::CheckedRun;
using top_sim_test::paper_phi_star;
using top_sim_test::run_checked;
using top_sim_test::scene_from;
using top_sim_test::standard_scene;

// The issue's accuracy target for the measured sleeping direction [rad].
constexpr double kPhiTolerance = 1e-3;

struct SweepCase {
  double alpha;
  double duration;  // > the reference time to reach 1e-3 rad, with the last 20 % after it
};

class RelaxationSweep : public ::testing::TestWithParam<SweepCase> {};

TEST_P(RelaxationSweep, SleepsAtTheAnalyticPhiStar) {
  const SweepCase c = GetParam();
  Simulator sim(scene_from(standard_scene(c.alpha, 200.0)));
  const CheckedRun r = run_checked(sim, c.duration, 1.0);
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_EQ(r.result.final.regime, Regime::sleeping) << to_string(r.result.final.regime);
  ASSERT_TRUE(r.result.phi_measured.has_value());
  // phi* = 2 atan(s_c (1 - sqrt(1 - tan(alpha)/mu_c))), evaluated here from physics.md section 5.
  const double phi_star = paper_phi_star(c.alpha, 0.25, 0.6);
  EXPECT_NEAR(*r.result.phi_measured, phi_star, kPhiTolerance);
  top_sim_test::note("alpha " + std::to_string(c.alpha) + ": phi_measured - phi*", *r.result.phi_measured - phi_star);
  top_sim_test::note("alpha " + std::to_string(c.alpha) + ": cpu_seconds", r.result.cpu_seconds);
  ASSERT_TRUE(r.result.phi_star.has_value());
  EXPECT_NEAR(*r.result.phi_star, phi_star, 1e-14);  // the reported analytic value is the same formula
  // The constrained model conserves E + W_diss; at rtol 1e-8 the drift over the run stays far below 1e-6.
  EXPECT_LT(r.result.max_energy_residual, 1e-6);
}

// Durations: reference times to 1e-3 rad are 1681, 549, 224, 67 s (0.02, 0.05, 0.1, 0.2; physics.md section 5).
INSTANTIATE_TEST_SUITE_P(StandardStart, RelaxationSweep,
                         ::testing::Values(SweepCase{0.02, 2000.0}, SweepCase{0.05, 700.0}, SweepCase{0.1, 300.0},
                                           SweepCase{0.15, 200.0}, SweepCase{0.2, 100.0}),
                         [](const ::testing::TestParamInfo<SweepCase>& info) {
                           return "alpha_" + std::to_string(std::lround(info.param.alpha * 1000)) + "mrad";
                         });

// Simulated phi_measured for a scene; fails the test on a fault or a non-finite sample.
double sleeping_phi(const Scene& scene, double duration, Regime* regime = nullptr) {
  Simulator sim(scene);
  const CheckedRun r = run_checked(sim, duration, 1.0);
  EXPECT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_EQ(r.result.final.regime, Regime::sleeping) << to_string(r.result.final.regime);
  if (regime) *regime = r.result.final.regime;
  top_sim_test::note(scene.source + ", spin " + std::to_string(scene.initial.spin) + ", m " +
                         std::to_string(scene.model.top.mass) + ": phi_measured - phi*",
                     r.result.phi_measured.value_or(NAN) - stationary_state(scene.model, scene.initial.spin).phi);
  return r.result.phi_measured.value_or(NAN);
}

TEST(RelaxationInvariance, PhiStarDoesNotDependOnTheSpinRate) {
  const double phi_star = paper_phi_star(0.1, 0.25, 0.6);
  // The relaxation is geometric: its time grows in proportion to the spin, so the duration is scaled with it.
  for (double spin : {100.0, 200.0, 400.0}) {
    SCOPED_TRACE("spin = " + std::to_string(spin));
    const double duration = 300.0 * spin / 200.0;
    EXPECT_NEAR(sleeping_phi(scene_from(standard_scene(0.1, spin)), duration), phi_star, kPhiTolerance);
  }
}

TEST(RelaxationInvariance, PhiStarDoesNotDependOnMassInertiaRadiusOrOffset) {
  const double phi_star = paper_phi_star(0.1, 0.25, 0.6);
  struct Variant {
    const char* name;
    const char* top;
    double duration;
  };
  // Two different bodies: the steel top file (m, R, f, I_f, I_d all differ), and a heavy, blunt, tall variant.
  const Variant variants[] = {
      {"steel", "top: steel\n", 300.0},
      {"heavy blunt tall",
       "top: {mass: 0.05, tip_radius: 2.5e-3, com_offset: 0.015, inertia_axial: 6.0e-6, inertia_transverse: 5.0e-6}\n",
       300.0},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.name);
    const std::string yaml = std::string(v.top) +
                             "plane: {inclination: 0.1}\n"
                             "friction: {law: paper, mu_c: 0.25, s_c: 0.6}\n"
                             "initial: {start: tilted, tilt: 0.1, spin: 200.0}\n";
    const Scene scene = scene_from(yaml);
    // Analytic: the solver's phi* for this body equals that of the formula (rounding).
    EXPECT_NEAR(stationary_state(scene.model, 200.0).phi, phi_star, 1e-14);
    // Simulated.
    EXPECT_NEAR(sleeping_phi(scene, v.duration), phi_star, kPhiTolerance);
  }
}

TEST(RelaxationInvariance, ReversedSpinSleepsAtPiMinusPhiStar) {
  const double phi_star = paper_phi_star(0.1, 0.25, 0.6);
  const Scene scene = load_scene(top_sim_test::scene_path("reversed_spin"));
  ASSERT_LT(scene.initial.spin, 0.0);
  // Analytic (rounding) and simulated (the issue's 1e-3 rad).
  EXPECT_NEAR(stationary_state(scene.model, scene.initial.spin).phi, M_PI - phi_star, 1e-14);
  EXPECT_NEAR(sleeping_phi(scene, scene.duration), M_PI - phi_star, kPhiTolerance);
}

// physics.md section 3: v_eps only removes a 0/0 and shifts phi* by ~4e-9 rad per 1e-9 m/s.
// Prediction: asleep, mu(s) = tan(alpha) fixes s = |v_t| / (|u| + v_h + v_eps) = s*, while the geometry gives
// tan(phi/2) = |v_t| / (|u| + v_h); so tan(phi/2) = s* (1 + eps), eps = v_eps / (|u| + v_h), and
// d phi = 2 s* / (1 + s*^2) * d eps.
TEST(Regularization, VepsDoesNotChangeTheSleepingDirectionMeasurably) {
  double phi[2];
  const double v_eps[2] = {1e-9, 1e-8};
  Snapshot last;
  for (int i = 0; i < 2; ++i) {
    Scene scene = load_scene(top_sim_test::scene_path("default"));
    scene.model.regularization_speed = v_eps[i];
    Simulator sim(scene);
    const CheckedRun r = run_checked(sim, scene.duration, 1.0);
    ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
    EXPECT_EQ(r.nonfinite, "");
    EXPECT_EQ(r.result.final.regime, Regime::sleeping);
    ASSERT_TRUE(r.result.phi_measured.has_value());
    phi[i] = *r.result.phi_measured;
    last = r.result.final;
  }
  // Not measurable against the 1e-3 rad target: 1e-6 is still 1000x below it.
  EXPECT_NEAR(phi[0], phi[1], 1e-6);
  const double s = top_sim_test::paper_slip_star(0.1, 0.25, 0.6);
  const double speeds = last.tip_velocity.norm() + 1.5e-3 * last.angular_velocity.cross(Eigen::Vector3d::UnitZ()).norm();
  const double predicted = 2 * s / (1 + s * s) * (v_eps[1] - v_eps[0]) / speeds;
  // The transient is the same in both runs, so the difference is the v_eps shift alone; 2e-9 (6 %) allows for the
  // integration error at rtol 1e-8.
  EXPECT_NEAR(phi[1] - phi[0], predicted, 2e-9);
  top_sim_test::note("phi_measured(v_eps 1e-8) - phi_measured(v_eps 1e-9)", phi[1] - phi[0]);
  top_sim_test::note("predicted shift", predicted);
}

// physics.md section 8 / consequence 1: nutating first, then precessing, finally sleeping.
TEST(Regimes, StandardStartNutatesThenPrecessesThenSleeps) {
  Simulator sim(load_scene(top_sim_test::scene_path("default")));
  std::vector<std::pair<double, Regime>> runs;  // (first time, regime) of each run of equal regimes
  double first[5] = {-1, -1, -1, -1, -1};
  double last_nutating = -1;
  const double dt = 0.02;
  for (int k = 0; k <= 300 / dt; ++k) {
    sim.advance_to(k * dt);
    const Snapshot s = sim.snapshot();
    ASSERT_EQ(top_sim_test::nonfinite_fields(s), "") << "t = " << s.t;
    const int r = static_cast<int>(s.regime);
    if (first[r] < 0) first[r] = s.t;
    if (s.regime == Regime::nutating) last_nutating = s.t;
    if (runs.empty() || runs.back().second != s.regime) runs.emplace_back(s.t, s.regime);
  }
  std::string seq;
  for (const auto& r : runs) seq += std::string(to_string(r.second)) + "@" + std::to_string(r.first) + " ";
  SCOPED_TRACE("regime sequence: " + seq);
  std::cout << "[ measured ] regime sequence (first time of each run, s): " << seq.substr(0, 400) << std::endl;
  ASSERT_FALSE(runs.empty());
  EXPECT_EQ(runs.front().second, Regime::nutating);
  EXPECT_EQ(runs.back().second, Regime::sleeping);
  const double t_prec = first[static_cast<int>(Regime::precessing)];
  const double t_sleep = first[static_cast<int>(Regime::sleeping)];
  ASSERT_GE(t_prec, 0.0) << "never precessing";
  ASSERT_GE(t_sleep, 0.0) << "never sleeping";
  EXPECT_LT(t_prec, t_sleep);
  // Once the nutation has died it does not come back (no forcing), so sleeping starts after the last nutation.
  EXPECT_LT(last_nutating, t_sleep);
  EXPECT_LT(first[static_cast<int>(Regime::sliding)], 0.0) << "no sliding below alpha_c from this start";
  EXPECT_LT(first[static_cast<int>(Regime::contact_fault)], 0.0);
}

// Static (N = m g cos alpha) and constrained normal force share the sleeping state (exact for both there).
TEST(NormalForceModels, StaticAndConstrainedSleepInTheSameState) {
  const double phi_star = paper_phi_star(0.1, 0.25, 0.6);
  const Eigen::Vector3d f_star = stationary_state(load_scene(top_sim_test::scene_path("default")).model, 1.0).f_hat;
  double phi[2];
  Eigen::Vector3d f_end[2];
  const NormalForceModel kinds[2] = {NormalForceModel::constrained, NormalForceModel::static_approximation};
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE(to_string(kinds[i]));
    Scene scene = load_scene(top_sim_test::scene_path("default"));
    scene.model.normal_force = kinds[i];
    Simulator sim(scene);
    const CheckedRun r = run_checked(sim, scene.duration, 1.0);
    ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
    EXPECT_EQ(r.nonfinite, "");
    EXPECT_EQ(r.result.final.regime, Regime::sleeping);
    phi[i] = r.result.phi_measured.value_or(NAN);
    f_end[i] = r.result.final.figure_axis;
    top_sim_test::note(std::string(to_string(kinds[i])) + ": max energy-balance residual", r.result.max_energy_residual);
    EXPECT_NEAR(phi[i], phi_star, kPhiTolerance);
    // Asleep the axis is f_hat*; the residual precession (phi within 1e-3) tilts it by far less than 1e-3 rad.
    EXPECT_LT(top_sim_test::angle_between(f_end[i], f_star), 1e-3);
  }
  EXPECT_NEAR(phi[0], phi[1], kPhiTolerance);
  EXPECT_LT(top_sim_test::angle_between(f_end[0], f_end[1]), 1e-3);
}

}  // namespace
