// Linear stability of the sleeping state (physics.md section 10, include/top_sim/stability.hpp): the spec's
// figures, the 1/spin scaling, stability exactly while s* < s_c (alpha_c from the eigenvalue crossing), the
// gyroscope-loaded top's unstable window, the finite-difference step, and the predicted relaxation time against
// the decay of |phi - phi*| in simulation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_util.hpp"
#include "top_sim/stability.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;
using top_sim_test::scene_from;
using top_sim_test::standard_scene;

constexpr double kSpin = 200.0;

// The default scene's top and friction (aluminium on PMMA: paper law, mu_c 0.25, s_c 0.6) at inclination alpha.
Model default_model(double alpha) {
  Model m = load_scene(top_sim_test::scene_path("default")).model;
  m.plane = make_plane(alpha, m.plane.gravity);
  return m;
}

TEST(StabilityCoordinates, ReduceInvertsExpandAndTheBasisIsOrthonormal) {
  const Model m = default_model(0.1);
  const StationaryState st = stationary_state(m, kSpin);
  const ReducedCoordinates rc = reduced_coordinates(m, st.f_hat);
  EXPECT_NEAR(rc.e1.dot(rc.e2), 0.0, 1e-15);
  EXPECT_NEAR(rc.e1.dot(rc.f_star), 0.0, 1e-15);
  EXPECT_NEAR(rc.e2.norm(), 1.0, 1e-15);
  Eigen::VectorXd z(7);
  z << 0.01, -0.02, 0.03, -0.04, 1.0, 2.0, 200.0;
  EXPECT_LT((reduce(rc, expand(rc, z)) - z).norm(), 1e-15);
}

// physics.md section 10: Re(precession) about -0.0052, -0.029, -0.084 1/s at alpha 0.02, 0.1, 0.2 (200 rad/s),
// friction modes about -1200 1/s at 0.02, one zero eigenvalue, the nutation pair near i I_f omega*/I_d.
TEST(SleepingStability, ReproducesTheSpecFigures) {
  struct Figure {
    double alpha, precession, tolerance;  // the spec's value and half a unit of its last digit
  };
  for (const Figure& fig : {Figure{0.02, -0.0052, 0.00005}, Figure{0.1, -0.029, 0.0005}, Figure{0.2, -0.084, 0.0005}}) {
    SCOPED_TRACE("alpha = " + std::to_string(fig.alpha));
    const StabilityResult r = sleeping_stability(default_model(fig.alpha), kSpin);
    ASSERT_TRUE(r.exists) << r.reason;
    EXPECT_NEAR(r.modes.precession.real(), fig.precession, fig.tolerance);
    note("alpha " + std::to_string(fig.alpha) + ": Re precession [1/s]", r.modes.precession.real());
    EXPECT_TRUE(r.stable);
    EXPECT_TRUE(r.resolved);
    EXPECT_EQ(r.eigenvalues.size(), 7u);
    EXPECT_EQ(r.modes.friction.size(), 2u);
    // Exactly one eigenvalue at zero (the free spin magnitude): the next smallest is the precession (|.| ~ 2.3).
    EXPECT_LT(std::abs(r.zero), 1e-10);
    for (const Eigenvalue& v : r.eigenvalues) {
      if (v != r.zero) {
        EXPECT_GT(std::abs(v), 1.0);
      }
    }
  }
  const StabilityResult low = sleeping_stability(default_model(0.02), kSpin);
  for (const Eigenvalue& v : low.modes.friction) EXPECT_NEAR(v.real(), -1200.0, 60.0);  // "about": 5 %
  note("alpha 0.02: Re friction [1/s]", low.modes.friction.front().real());
  // The nutation: near i I_f omega / I_d (333 1/s) where the friction is soft (alpha 0.2: 2.4 % below); where it is
  // stiff (alpha 0.02) the contact nearly rolls and the frequency falls towards the rolling top's
  // I_f omega / (I_d + m (R + f)^2) = 159 1/s (measured 170).
  const Top top = default_model(0.1).top;
  const double free_nutation = top.inertia_axial * kSpin / top.inertia_transverse;
  const double rolling_nutation =
      top.inertia_axial * kSpin / (top.inertia_transverse + top.mass * std::pow(top.tip_radius + top.com_offset, 2));
  const StabilityResult high = sleeping_stability(default_model(0.2), kSpin);
  EXPECT_NEAR(high.modes.nutation.imag(), free_nutation, 0.03 * free_nutation);
  EXPECT_GT(low.modes.nutation.imag(), rolling_nutation);
  EXPECT_LT(low.modes.nutation.imag(), 1.1 * rolling_nutation);
  note("alpha 0.2: Im nutation / (I_f omega / I_d)", high.modes.nutation.imag() / free_nutation);
  note("alpha 0.02: Im nutation / (I_f omega / (I_d + m (R + f)^2))", low.modes.nutation.imag() / rolling_nutation);
}

// The precession's decay rate scales as 1/omega* for a fast top (physics.md: relaxation is geometric).
TEST(SleepingStability, PrecessionRateScalesAsOneOverTheSpin) {
  for (double alpha : {0.02, 0.1, 0.2}) {
    SCOPED_TRACE("alpha = " + std::to_string(alpha));
    const Model m = default_model(alpha);
    auto product = [&m](double w) { return sleeping_stability(m, w).modes.precession.real() * w; };
    // Re * omega at 200, 400, 800 rad/s: within 2.5 % from 200 to 400 (measured 0.3 to 1.5 %), 0.5 % from 400
    // to 800 (0.04 to 0.4 %): the 1/omega law is approached from above as the top gets faster.
    EXPECT_NEAR(product(200.0) / product(400.0), 1.0, 0.025);
    EXPECT_NEAR(product(400.0) / product(800.0), 1.0, 0.005);
    // The reversed spin has the same spectrum.
    EXPECT_NEAR(sleeping_stability(m, -kSpin).modes.precession.real(), product(kSpin) / kSpin, 1e-12);
    note("alpha " + std::to_string(alpha) + ": Re(200) / Re(400)",
         sleeping_stability(m, 200.0).modes.precession.real() / sleeping_stability(m, 400.0).modes.precession.real());
  }
}

// physics.md sections 5 and 10: for the paper law the sleeping state is stable exactly while s* < s_c.
TEST(SleepingStability, StableExactlyWhileTheSlipIsBelowSc) {
  const Model m = default_model(0.05);
  int unstable_roots = 0;
  for (double alpha = 0.005; alpha < std::atan(0.25); alpha += 0.005) {
    const Model ma = default_model(alpha);
    const StabilityResult stable_root = sleeping_stability(ma, kSpin);
    ASSERT_TRUE(stable_root.exists) << alpha;
    EXPECT_TRUE(stable_root.stable) << "alpha " << alpha << ": max Re " << stable_root.max_real;
    // The other root s_c (1 + sqrt(1 - tan(alpha)/mu_c)) lies in [0, 1] from alpha 0.138 on.
    const StationaryState st = stationary_state(ma, kSpin);
    if (st.slip_unstable < 0.0) continue;
    ++unstable_roots;
    const StabilityResult unstable_root = stability_at(ma, stationary_state_on_root(ma, kSpin, st.slip_unstable), kSpin);
    ASSERT_TRUE(unstable_root.exists);
    EXPECT_FALSE(unstable_root.stable) << "alpha " << alpha;
    EXPECT_GT(unstable_root.max_real, 0.0) << "alpha " << alpha;
  }
  EXPECT_GE(unstable_roots, 20);
  for (double ds : {1e-2, 1e-4, 1e-6}) {
    EXPECT_TRUE(stability_on_branch(m, kSpin, 0.0, 0.6 - ds).stable) << "s_c - " << ds;
    EXPECT_GT(stability_on_branch(m, kSpin, 0.0, 0.6 + ds).max_real, 0.0) << "s_c + " << ds;
  }
}

// alpha_c where the eigenvalue crosses (bisection along the slip branch) against the analytic alpha_c of
// stationary.hpp and atan(mu_c), for three s_c. The crossing is a friction mode through zero at s = s_c (a
// fold); next to the zero eigenvalue of the spin the two near-zero eigenvalues are resolved to ~1e-8 1/s, which
// places the crossing to ~3e-9 in s (measured 1.0e-9 to 2.3e-9); alpha(s) is flat at s_c, so alpha_c agrees to
// rounding.
TEST(SleepingStability, EigenvalueCrossingLocatesAlphaC) {
  for (double s_c : {0.3, 0.6, 0.9}) {
    SCOPED_TRACE("s_c = " + std::to_string(s_c));
    Model m = default_model(0.05);
    m.friction.s_c = s_c;
    const StabilityCrossing c = locate_stability_loss(m, kSpin);
    ASSERT_TRUE(c.found) << c.reason;
    EXPECT_EQ(c.mode, "friction");
    EXPECT_GT(c.eigenvalue.real(), 0.0);
    EXPECT_NEAR(c.slip, s_c, 1e-7);
    EXPECT_NEAR(c.alpha, critical_inclination(m.friction), 1e-12);
    EXPECT_NEAR(c.alpha, std::atan(m.friction.mu_c), 1e-12);
    note("s_c " + std::to_string(s_c) + ": s at the crossing - s_c", c.slip - s_c);
    note("s_c " + std::to_string(s_c) + ": alpha at the crossing - atan(mu_c)", c.alpha - std::atan(m.friction.mu_c));
  }
}

TEST(SleepingStability, FiniteDifferenceStepDoesNotMatter) {
  for (double alpha : {0.02, 0.1, 0.2}) {
    SCOPED_TRACE("alpha = " + std::to_string(alpha));
    const Model m = default_model(alpha);
    const StabilityResult base = sleeping_stability(m, kSpin);
    EXPECT_LT(base.precession_error, 1e-8);
    StabilityOptions variants[3];
    variants[0].step *= 4.0;
    variants[1].step /= 4.0;
    variants[2].richardson = true;
    for (const StabilityOptions& o : variants) {
      const StabilityResult r = sleeping_stability(m, kSpin, 0.0, o);
      // The slow eigenvalues to 1e-8 1/s (measured <= 1e-9), the fast ones to 1e-7 relative.
      EXPECT_NEAR(r.modes.precession.real(), base.modes.precession.real(), 1e-8);
      EXPECT_NEAR(r.modes.precession.imag(), base.modes.precession.imag(), 1e-7);
      EXPECT_NEAR(std::abs(r.modes.nutation - base.modes.nutation), 0.0, 1e-7 * std::abs(base.modes.nutation));
      for (std::size_t i = 0; i < r.modes.friction.size(); ++i)
        EXPECT_NEAR(std::abs(r.modes.friction[i] - base.modes.friction[i]), 0.0, 1e-7 * std::abs(base.modes.friction[i]));
    }
  }
}

TEST(SleepingStability, NoAnalysisWithoutAMovingSleepingState) {
  const StabilityResult above = sleeping_stability(default_model(0.3), kSpin);
  EXPECT_FALSE(above.exists);
  EXPECT_NE(above.reason.find("slides downhill"), std::string::npos) << above.reason;
  const StabilityResult level = sleeping_stability(default_model(0.0), kSpin);
  EXPECT_FALSE(level.exists);
  EXPECT_NE(level.reason.find("kink"), std::string::npos) << level.reason;
  // A contact that sticks (Coulomb friction above tan(alpha)) sits at the kink v_t = 0.
  const StabilityResult sticks = sleeping_stability(load_scene(top_sim_test::scene_path("coulomb")).model, kSpin);
  EXPECT_FALSE(sticks.exists);
  EXPECT_NE(sticks.reason.find("sticks"), std::string::npos) << sticks.reason;
  // Spins whose sleeping speed is within 100 v_eps are the regularisation's, not the law's.
  EXPECT_FALSE(sleeping_stability(default_model(0.1), 1e-5).exists);
}

// physics.md sections 6 and 10: the gyroscope-loaded top (config/scenes/gyro_reversal.yaml: rotor 2000 rad/s) is
// briefly unstable near zero shell spin, nutation Re about +2.5 1/s at |omega_t| < 0.5 rad/s.
TEST(GyrostatStability, NutationIsUnstableJustBelowZeroShellSpin) {
  const Scene scene = load_scene(top_sim_test::scene_path("gyro_reversal"));
  const double rotor = scene.initial.rotor_spin;
  ASSERT_EQ(rotor, 2000.0);
  const auto windows = unstable_spin_windows(scene.model, rotor, -2.0, 2.0, 81, WatchedMode::nutation);
  ASSERT_EQ(windows.size(), 1u);
  // The window: from -0.552 rad/s up to zero shell spin (to within the v_eps layer, 4e-4 rad/s); only on the side
  // where the shell spins against the rotor.
  EXPECT_NEAR(windows[0].lower, -0.55, 0.01);
  EXPECT_LT(windows[0].upper, 0.0);
  EXPECT_GT(windows[0].upper, -1e-3);
  note("gyrostat nutation window lower edge [rad/s]", windows[0].lower);
  note("gyrostat nutation window upper edge [rad/s]", windows[0].upper);
  note("gyrostat largest Re nutation on the scan [1/s]", windows[0].max_real);
  const StabilityResult at = sleeping_stability(scene.model, -0.2, rotor);
  EXPECT_NEAR(at.modes.nutation.real(), 2.5, 0.1);
  note("gyrostat Re nutation at -0.2 rad/s", at.modes.nutation.real());
  EXPECT_LT(sleeping_stability(scene.model, 0.2, rotor).modes.nutation.real(), -1.0);
  EXPECT_LT(sleeping_stability(scene.model, -20.0, rotor).modes.nutation.real(), -1.0);
  // The bearing's mode, -c (1/J + 1/I_f').
  ASSERT_EQ(at.modes.bearing.size(), 1u);
  EXPECT_NEAR(at.modes.bearing[0].real(), -1.5e-9 * (1.0 / 2e-6 + 1.0 / 3e-6), 1e-9);
  // With nu != 0 the bearing drags the spin: the frozen precession grows slowly (Re ~ +1.4e-3 1/s, proportional to
  // c nu; docs/analysis.md); with the bearing removed (c = 0: an exact equilibrium) it decays.
  EXPECT_GT(at.residual, 1.0);
  Model no_bearing = scene.model;
  no_bearing.top.rotor.coupling = 0.0;
  EXPECT_LT(sleeping_stability(no_bearing, -20.0, rotor).modes.precession.real(), 0.0);
}

// Amplitude envelope: the largest transverse shell angular velocity |omega - (omega . f) f| in each window.
std::vector<std::pair<double, double>> nutation_envelope(Simulator& sim, double duration, double window) {
  std::vector<std::pair<double, double>> out;
  const int per = 50;  // samples per window: 12 per nutation period at 633 1/s
  for (int k = 1; k <= std::lround(duration / window); ++k) {
    double amp = 0.0;
    for (int j = 1; j <= per; ++j) {
      sim.advance_to((k - 1 + double(j) / per) * window);
      const Eigen::Vector3d f = figure_axis(sim.state()).normalized(), w = angular_velocity(sim.state());
      amp = std::max(amp, (w - w.dot(f) * f).norm());
    }
    out.emplace_back(sim.time(), amp);
  }
  return out;
}

// Least-squares slope of log(value) against t, and the squared correlation.
std::pair<double, double> log_slope(const std::vector<std::pair<double, double>>& points) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (const auto& [t, v] : points) {
    const double y = std::log(v);
    n += 1; sx += t; sy += y; sxx += t * t; sxy += t * y; syy += y * y;
  }
  const double cov = n * sxy - sx * sy;
  return {cov / (n * sxx - sx * sx), cov * cov / ((n * sxx - sx * sx) * (n * syy - sy * sy))};
}

// The window in simulation: frozen at -0.2 rad/s (bearing off, so the state is an exact equilibrium), a
// 1e-7 rad change of the inclination seeds every mode; the nutation grows at the predicted rate.
TEST(GyrostatStability, SimulatedNutationGrowsAtThePredictedRate) {
  const std::string yaml =
      "top: {mass: 0.025, tip_radius: 1.5e-3, com_offset: 0.010, inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6,"
      " rotor: {inertia_axial: 2.0e-6, coupling: 0.0, spin: 2000.0}}\n"
      "plane: {inclination: 0.07}\nfriction: pmma\ninitial: {start: stationary, spin: -0.2}\n"
      "events:\n  - {t: 0.0, inclination: 0.0700001}\n";
  const Scene scene = scene_from(yaml);
  const double predicted = sleeping_stability(scene.model, -0.2, 2000.0).modes.nutation.real();
  Simulator sim(scene);
  const auto envelope = nutation_envelope(sim, 5.0, 0.05);
  ASSERT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  // The last two thirds (the friction modes and the seed's transient gone): amplitude 1e-6 to 4e-2 rad/s, linear.
  const auto [slope, r2] = log_slope({envelope.begin() + envelope.size() / 3, envelope.end()});
  EXPECT_NEAR(slope, predicted, 0.05 * predicted);
  EXPECT_GT(r2, 0.999);
  note("gyrostat at -0.2 rad/s: simulated nutation growth rate [1/s]", slope);
  note("gyrostat at -0.2 rad/s: predicted Re nutation [1/s]", predicted);
}

// Predicted relaxation time 1/|Re precession| against the measured decay of |phi - phi*| in the simulation
// (standard tilted start of test/core/relaxation_test.cpp). |phi - phi*| oscillates at the precession frequency;
// its peaks decay exponentially once the nutation has died: fit log(peak) against t over the late, linear part,
// where the peaks lie between 1e-4 and 1e-7 rad (above the floor of ~4e-9 rad that v_eps puts between the
// simulated and the analytic phi*, physics.md section 5).
struct Decay {
  double predicted, measured, r2, final_spin, cpu;
  int peaks;
};

Decay measure_decay(double alpha) {
  Simulator sim(scene_from(standard_scene(alpha, kSpin)));
  const double t0 = top_sim::thread_cpu_seconds();
  std::vector<std::pair<double, double>> peaks;
  double prev2 = 0.0, prev1 = 0.0, t_prev = 0.0;
  bool late = false;
  const double rate = 10.0;  // samples per second: 27 per precession period (2.75 s)
  for (long k = 1; k <= 6000 * rate; ++k) {
    sim.advance_to(k / rate);
    const Snapshot s = sim.snapshot();
    const double d = std::abs(s.phi - s.phi_star);
    if (k > 2 && prev1 > prev2 && prev1 >= d) {  // a peak at the previous sample
      if (prev1 < 1e-4) late = true;
      if (late && prev1 < 1e-7) break;
      if (late) peaks.emplace_back(t_prev, prev1);
    }
    prev2 = prev1;
    prev1 = d;
    t_prev = s.t;
  }
  Decay out;
  out.cpu = top_sim::thread_cpu_seconds() - t0;
  out.final_spin = sim.snapshot().spin;
  // The sleeping spin has settled a little below the initial 200 rad/s: predict at the simulated one.
  out.predicted = sleeping_stability(sim.model(), out.final_spin).relaxation_time;
  const auto [slope, r2] = log_slope(peaks);
  out.measured = -1.0 / slope;
  out.r2 = r2;
  out.peaks = static_cast<int>(peaks.size());
  return out;
}

class RelaxationPrediction : public ::testing::TestWithParam<double> {};

TEST_P(RelaxationPrediction, MatchesTheSimulatedDecayOfPhi) {
  const double alpha = GetParam();
  const Decay d = measure_decay(alpha);
  ASSERT_GE(d.peaks, 30);
  EXPECT_GT(d.r2, 0.999);  // the fitted part is linear in log
  EXPECT_NEAR(d.measured, d.predicted, 0.05 * d.predicted);
  const std::string tag = "alpha " + std::to_string(alpha) + ": ";
  note(tag + "predicted relaxation time [s]", d.predicted);
  note(tag + "simulated relaxation time [s]", d.measured);
  note(tag + "simulated / predicted - 1", d.measured / d.predicted - 1.0);
  note(tag + "sleeping spin [rad/s]", d.final_spin);
  note(tag + "peaks fitted", d.peaks);
  note(tag + "cpu_seconds", d.cpu);
}

INSTANTIATE_TEST_SUITE_P(StandardStart, RelaxationPrediction, ::testing::Values(0.02, 0.05, 0.1, 0.15, 0.2),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return "alpha_" + std::to_string(std::lround(info.param * 1000)) + "mrad";
                         });

}  // namespace
