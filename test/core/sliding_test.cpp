// No sleeping state reachable (physics.md section 5, consequence 3): above alpha_c, and just below it from the
// standard start (fully slipping, tan(alpha) > mu(1)), the top accelerates downhill, phi -> pi/2, s -> 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_util.hpp"

namespace {

using namespace top_sim;
using top_sim_test::CheckedRun;
using top_sim_test::run_checked;
using top_sim_test::scene_from;
using top_sim_test::standard_scene;

const double kAlphaC = std::atan(0.25);  // paper law mu_c = 0.25

// Centre-of-mass velocity component downhill (-e_y in the plane frame).
double downhill(const Snapshot& s) { return -s.com_velocity.y(); }

// Snapshot nearest to time t in a 1 Hz sampled run.
const Snapshot& at(const CheckedRun& r, double t) {
  const std::size_t k = static_cast<std::size_t>(std::lround(t));
  EXPECT_LT(k, r.snapshots.size());
  return r.snapshots.at(std::min(k, r.snapshots.size() - 1));
}

// Lower bound on the downhill speed gain while every sample has slip >= s_min (mu decreasing there, so mu <= mu(s_min)):
// m dv_d/dt >= m g sin(alpha) - mu(s_min) N; N averages m g cos(alpha) (the centre of mass stays at bounded
// height), and 0.9 allows for its nutation ripple.
double min_gain(double alpha, double mu_max, double dt) {
  return 0.9 * 9.81 * (std::sin(alpha) - mu_max * std::cos(alpha)) * dt;
}
// Upper bound: friction never pushes downhill once the contact slides downhill, so dv_d/dt <= g sin(alpha) (+1 %).
double max_gain(double alpha, double dt) { return 1.01 * 9.81 * std::sin(alpha) * dt; }

TEST(Supercritical, AcceleratesDownhillTowardsPiOverTwoAndSlides) {
  const Scene scene = load_scene(top_sim_test::scene_path("supercritical"));
  const double alpha = scene.model.plane.inclination;
  ASSERT_GT(alpha, kAlphaC);
  Simulator sim(scene);
  const CheckedRun r = run_checked(sim, 20.0, 1.0, true);
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_EQ(r.nonfinite, "");
  // No stationary state: phi* absent, with the reason.
  EXPECT_FALSE(r.result.phi_star.has_value());
  EXPECT_NE(r.result.stationary_note.find("alpha_c"), std::string::npos) << r.result.stationary_note;
  for (const Snapshot& s : r.snapshots) {
    EXPECT_EQ(s.regime, Regime::sliding) << "t = " << s.t;
    EXPECT_FALSE(s.has_stationary_state);
  }
  // Speed grows at every sample after the first second.
  for (int t = 2; t <= 20; ++t) EXPECT_GT(downhill(at(r, t)), downhill(at(r, t - 1))) << "t = " << t;
  const double gain = downhill(at(r, 20)) - downhill(at(r, 10));
  EXPECT_GT(gain, min_gain(alpha, 0.25, 10.0));  // mu <= mu_c everywhere
  EXPECT_LT(gain, max_gain(alpha, 10.0));
  // phi -> pi/2: the rolling part (bounded) becomes negligible against the growing downhill sliding.
  const double dev10 = std::abs(at(r, 10).phi - M_PI / 2), dev20 = std::abs(at(r, 20).phi - M_PI / 2);
  EXPECT_LT(dev20, dev10);
  EXPECT_LT(dev20, 0.01);  // ~ v_h / v_d with v_h ~ 0.05 m/s and v_d > 10 m/s
  ASSERT_TRUE(r.result.phi_measured.has_value());
  EXPECT_NEAR(*r.result.phi_measured, M_PI / 2, 0.01);
  // s -> 1 (s = 1 - O(v_h / |u|)).
  EXPECT_GT(r.result.final.slip, 0.99);
  top_sim_test::note("supercritical: |phi(20 s) - pi/2|", dev20);
  top_sim_test::note("supercritical: downhill speed gain 10-20 s [m/s]", gain);
}

TEST(Supercritical, JustAboveAlphaCSlides) {
  const double alpha = kAlphaC + 1e-3;
  Simulator sim(scene_from(standard_scene(alpha, 200.0)));
  const CheckedRun r = run_checked(sim, 30.0, 1.0, true);
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_FALSE(r.result.final.has_stationary_state);
  EXPECT_EQ(r.result.final.regime, Regime::sliding);
  for (int t = 11; t <= 30; ++t) EXPECT_GT(downhill(at(r, t)), downhill(at(r, t - 1))) << "t = " << t;
  EXPECT_LT(std::abs(at(r, 30).phi - M_PI / 2), std::abs(at(r, 10).phi - M_PI / 2));
}

TEST(Supercritical, JustBelowAlphaCTheStandardStartRunsAway) {
  const double alpha = kAlphaC - 1e-3;
  const Scene scene = scene_from(standard_scene(alpha, 200.0));
  // A sleeping state exists (analytically) ...
  ASSERT_TRUE(stationary_state(scene.model, 200.0).exists);
  // ... but the start has s = 1 and tan(alpha) > mu(1) = mu_c (2 s_c - 1)/s_c^2, so it is never reached.
  const double mu1 = 0.25 * (2 * 0.6 - 1) / (0.6 * 0.6);
  ASSERT_GT(std::tan(alpha), mu1);
  Simulator sim(scene);
  const CheckedRun r = run_checked(sim, 40.0, 1.0, true);
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_EQ(r.nonfinite, "");
  EXPECT_EQ(r.result.final.regime, Regime::sliding);
  for (int t = 2; t <= 40; ++t) EXPECT_GT(downhill(at(r, t)), downhill(at(r, t - 1))) << "t = " << t;
  // Once s >= 0.99 everywhere on [20, 40] s, mu <= mu(0.99) and the gain has the lower bound above.
  double s_min = 1.0;
  for (int t = 20; t <= 40; ++t) s_min = std::min(s_min, at(r, t).slip);
  EXPECT_GT(s_min, 0.99);
  const double mu099 = 0.25 * 0.99 * (2 * 0.6 - 0.99) / 0.36;
  const double gain = downhill(at(r, 40)) - downhill(at(r, 20));
  EXPECT_GT(gain, min_gain(alpha, mu099, 20.0));
  EXPECT_LT(gain, max_gain(alpha, 20.0));
  top_sim_test::note("alpha_c - 1e-3: downhill speed gain 20-40 s [m/s]", gain);
  top_sim_test::note("alpha_c - 1e-3: min slip 20-40 s", s_min);
}

}  // namespace
