// A tippe top's spinning upright and inverted states (include/top_sim/stability.hpp, docs/analysis.md): the
// eigenvalue crossing against Magnus' critical spin in the four regions of (sign a, sign(I3/I1 - r/h)), the
// verdict on both sides of it against the linearised criterion c omega^2 < m g a, the crossing's independence of
// the friction coefficient, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "test_util.hpp"
#include "top_sim/stability.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;

// tippe_top.yaml (Cohen's sphere: R 2.5 cm, f = -0.5 cm, m 15 g, regularised Coulomb 0.3, v_eps 1 cm/s) with
// I3 = ratio * I1.
Model tippe_model(double ratio) {
  Model m = load_scene(top_sim_test::scene_path("tippe_top")).model;
  m.top.inertia_axial = ratio * m.top.inertia_transverse;
  return m;
}

// The reference, written out here from docs/analysis.md (not through the library): a > 0 when the centre of mass
// lies below the sphere's centre, h = r - a, c = (r/h) (I1 r/h - I3); stable exactly where c omega^2 < m g a, so
// omega_k^2 = m g a / c (Leine & Glocker's -a m g / ((r/h) I1 (I3/I1 - r/h))).
struct Reference {
  double a, ratio_minus_r_over_h, c, mga;
  double omega_k2() const { return mga / c; }
  bool stable(double w) const { return c * w * w < mga; }
};

Reference reference(const Model& m, SpinningState state) {
  const double r = m.top.tip_radius, f = m.top.com_offset;
  const double a = state == SpinningState::upright ? -f : f;  // f < 0: upright has the centre of mass below
  const double x = r / (r - a);
  const double I1 = m.top.inertia_transverse, I3 = m.top.inertia_axial;
  return {a, I3 / I1 - x, x * (I1 * x - I3), m.top.mass * m.plane.gravity * a};
}

// Three inertia ratios (below r/(r+|f|) = 0.833, between it and r/(r-|f|) = 1.25, above) times two states: the
// four regions of (a > 0 or < 0) x (I3/I1 > or < r/h), four of the six cases with a crossing.
TEST(SpinningStability, MagnusCrossingAndVerdictsInAllFourRegions) {
  std::set<std::pair<bool, bool>> regions;
  int crossings = 0;
  for (const double ratio : {0.7, 1.0, 1.5}) {
    for (const SpinningState state : {SpinningState::upright, SpinningState::inverted}) {
      SCOPED_TRACE("I3/I1 = " + std::to_string(ratio) + ", " + to_string(state));
      const Model m = tippe_model(ratio);
      const Reference ref = reference(m, state);
      regions.insert({ref.a > 0.0, ref.ratio_minus_r_over_h > 0.0});
      EXPECT_NEAR(magnus_critical_spin_squared(m, state) / ref.omega_k2(), 1.0, 1e-14);
      const double scale = std::sqrt(std::abs(ref.omega_k2()));  // omega_k, or the spin scale without a crossing
      for (const double w : {0.5 * scale, 2.0 * scale}) {
        const StabilityResult r = spinning_stability(m, state, w);
        ASSERT_TRUE(r.exists) << r.reason;
        EXPECT_EQ(r.stable, ref.stable(w)) << "spin " << w << ", max Re " << r.max_real;
      }
      // The crossing: the edges of the unstable windows on [0, 4 scale], bisected.
      const auto windows = unstable_spin_windows(m, state, 0.0, 0.0, 4.0 * scale, 41, WatchedMode::any);
      if (ref.omega_k2() > 0.0) {
        ++crossings;
        ASSERT_EQ(windows.size(), 1u);
        const double edge = ref.a > 0.0 ? windows[0].lower : windows[0].upper;  // unstable above / below omega_k
        EXPECT_NEAR(edge / scale, 1.0, 1e-6);
        note(std::string(to_string(state)) + " I3/I1 " + std::to_string(ratio) + ": crossing / omega_k - 1",
             edge / scale - 1.0);
      } else if (ref.a > 0.0) {
        EXPECT_TRUE(windows.empty());  // stable at every spin
      } else {
        ASSERT_EQ(windows.size(), 1u);  // unstable at every spin
        EXPECT_EQ(windows[0].lower, 0.0);
        EXPECT_EQ(windows[0].upper, 4.0 * scale);
      }
    }
  }
  EXPECT_EQ(regions.size(), 4u);
  EXPECT_EQ(crossings, 4);
}

// omega_k holds for any friction linear in the slip: the crossing moves by less than 1e-6 when the linear friction
// coefficient mu N / v_eps changes 60-fold (mu 0.3 -> 0.05, v_eps 1 cm/s -> 10 cm/s), while Re at 2 omega_k does.
TEST(SpinningStability, CrossingDoesNotDependOnTheFrictionCoefficient) {
  Model soft = tippe_model(1.0);
  soft.friction.mu = 0.05;
  soft.regularization_speed = 0.1;
  for (const SpinningState state : {SpinningState::upright, SpinningState::inverted}) {
    SCOPED_TRACE(to_string(state));
    const double w_k = std::sqrt(reference(soft, state).omega_k2());
    const auto windows = unstable_spin_windows(soft, state, 0.0, 0.0, 4.0 * w_k, 41, WatchedMode::any);
    ASSERT_EQ(windows.size(), 1u);
    const double edge = state == SpinningState::upright ? windows[0].lower : windows[0].upper;
    EXPECT_NEAR(edge / w_k, 1.0, 1e-6);
    const double stiff_re = spinning_stability(tippe_model(1.0), state, 2.0 * w_k).max_real;
    const double soft_re = spinning_stability(soft, state, 2.0 * w_k).max_real;
    EXPECT_GT(std::abs(stiff_re - soft_re), 0.1 * std::abs(stiff_re));
  }
}

TEST(SpinningStability, TheStateIsAnEquilibriumWithTheContactAtRest) {
  const Model m = tippe_model(1.0);
  for (const SpinningState state : {SpinningState::upright, SpinningState::inverted}) {
    const StateVector y = spinning_state(m, state, 100.0);
    const double sign = state == SpinningState::upright ? 1.0 : -1.0;
    EXPECT_EQ(figure_axis(y), Eigen::Vector3d(0.0, 0.0, sign));
    EXPECT_EQ(angular_velocity(y), Eigen::Vector3d(0.0, 0.0, 100.0 * sign));
    EXPECT_EQ(in_plane_velocity(y).norm(), 0.0);
    const StabilityResult r = spinning_stability(m, state, 100.0);
    ASSERT_TRUE(r.exists) << r.reason;
    EXPECT_LT(r.residual, 1e-12);
    EXPECT_EQ(r.eigenvalues.size(), 7u);
    EXPECT_LT(std::abs(r.zero), 1e-9);  // the free spin
    EXPECT_TRUE(r.resolved);
  }
}

TEST(SpinningStability, RefusesWhatItCannotAnalyseNamingTheField) {
  const Model tippe = tippe_model(1.0);
  Model ordinary = tippe;
  ordinary.top.com_offset = 0.01;
  Model tilted = tippe;
  tilted.plane = make_plane(0.1, tippe.plane.gravity);
  Model short_tilt = tippe;
  short_tilt.top.max_tilt = 1.2;
  Model paper = tippe;
  paper.friction.kind = FrictionLawKind::paper;
  const std::pair<const Model*, std::string> cases[] = {{&ordinary, "top.com_offset = 0.01"},
                                                        {&tilted, "plane.inclination = 0.1"},
                                                        {&short_tilt, "top.max_tilt = 1.2"},
                                                        {&paper, "mu(0) = 0"}};
  for (const auto& [model, says] : cases) {
    const StabilityResult r = spinning_stability(*model, SpinningState::inverted, 100.0);
    EXPECT_FALSE(r.exists);
    EXPECT_NE(r.reason.find(says), std::string::npos) << r.reason;
  }
  EXPECT_TRUE(spinning_stability(short_tilt, SpinningState::upright, 100.0).exists);  // upright needs no tilt range
}

}  // namespace
