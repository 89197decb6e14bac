// The wake-up (issue 32 part 5, docs/results.md "The wake-up"): config/scenes/spin_down.yaml spins down on a Hertz
// patch; the growth rate of its small tilt, measured from the simulated tilt, changes sign above the upright state's
// frozen critical spin (locate_critical_spin), at the zero of the slow passage's rate (passage_growth_rate); the
// passage delays the fall; the run ends at the end state `fallen`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "test_util.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stability.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;

constexpr double kSample = 0.01;    // [s] sampling of the run: well inside a precession period (0.2 s or more)
constexpr double kWindow = 2.0;     // [s] growth-rate window, as scripts/plots/spin_down.py: many precession periods
constexpr double kFallTilt = 0.5;   // [rad] the visible fall

struct Sample {
  double t, spin, tilt;
};

struct WindowRate {
  double t, spin, rate;  // window midpoint pair: time, mean spin, d ln(peak tilt)/dt
};

// The run, sampled, until its end (the fall) or the scene's duration.
std::vector<Sample> run(Simulator& sim, double duration) {
  std::vector<Sample> out;
  for (double t = 0.0; t <= duration && !sim.stopped(); t += kSample) {
    sim.advance_to(t);
    const Eigen::Vector3d f = figure_axis(sim.state()).normalized();
    const double spin = angular_velocity(sim.state()).dot(f);
    out.push_back({sim.time(), spin, std::acos(std::clamp(f.z(), -1.0, 1.0))});
  }
  return out;
}

// d ln(peak tilt)/dt between consecutive windows (the envelope: nutation and precession averaged out).
std::vector<WindowRate> window_rates(const std::vector<Sample>& s, double window = kWindow) {
  std::vector<double> mid, peak, spin;
  for (std::size_t i = 0; i < s.size();) {
    const double lo = s[i].t;
    double p = 0.0, w = 0.0;
    int n = 0;
    for (; i < s.size() && s[i].t < lo + window; ++i, ++n) {
      p = std::max(p, s[i].tilt);
      w += s[i].spin;
    }
    if (n < 0.9 * window / kSample) break;  // a partial window at the fall
    mid.push_back(lo + 0.5 * window);
    peak.push_back(std::log(p));
    spin.push_back(w / n);
  }
  std::vector<WindowRate> r;
  for (std::size_t k = 1; k < mid.size(); ++k)
    r.push_back({0.5 * (mid[k] + mid[k - 1]), 0.5 * (spin[k] + spin[k - 1]),
                 (peak[k] - peak[k - 1]) / (mid[k] - mid[k - 1])});
  return r;
}

// The spin where the rate turns positive for good (linear in the spin between the two windows around it).
double sign_change_spin(const std::vector<WindowRate>& r) {
  std::size_t k = r.size();
  while (k > 0 && r[k - 1].rate > 0.0) --k;
  if (k == 0 || k == r.size()) return NAN;
  const WindowRate &a = r[k - 1], &b = r[k];
  return a.spin + (b.spin - a.spin) * (0.0 - a.rate) / (b.rate - a.rate);
}

TEST(WakeUp, GrowthRateChangesSignAtTheCriticalSpinAndTheTopFalls) {
  const Scene scene = load_scene(top_sim_test::scene_path("spin_down"));
  const double w_start = scene.initial.spin;
  // The tool's critical spin, scanned below the start spin (where the scene's top is stable).
  const CriticalSpin c = locate_critical_spin(scene.model, SpinningState::upright, 0.0, 0.01 * w_start, w_start, 200);
  ASSERT_TRUE(c.found) << c.reason;
  note("tool critical spin [rad/s]", c.spin);
  note("Maxwell-Klein [rad/s]", maxwell_klein_critical_spin(scene.model));

  Simulator sim(scene);
  const std::vector<Sample> s = run(sim, scene.duration);
  ASSERT_EQ(sim.end_state(), EndState::fallen) << "t = " << sim.time() << ": " << sim.fault_message();
  EXPECT_EQ(sim.fault(), ContactFault::none);
  EXPECT_LT(sim.time(), scene.duration);
  for (const Sample& x : s) ASSERT_TRUE(std::isfinite(x.tilt) && std::isfinite(x.spin)) << "t = " << x.t;
  note("fallen at t [s]", sim.time());
  note("spin at the fall [rad/s]", s.back().spin);

  const std::vector<WindowRate> r = window_rates(s);
  const double w_sim = sign_change_spin(r);
  note("simulated sign change of d ln tilt/dt [rad/s]", w_sim);
  note("simulated / tool - 1", w_sim / c.spin - 1.0);
  // Measured (docs/results.md): the tilt turns to growth 26 % above the frozen critical spin, because the spin
  // changes (0.18 rad/s^2) at a rate comparable to the frozen growth rates (1e-3 1/s): the passage is not
  // quasi-static (passage_growth_rate() below accounts for it). Asserted here: above the frozen value, within 30 %.
  EXPECT_GT(w_sim, c.spin);
  EXPECT_LT(w_sim / c.spin, 1.30);
  // The simulated rate exceeds the frozen largest Re at every window from the start to the fall's last e-folds.
  for (const WindowRate& x : r) {
    if (x.rate > 0.1) break;           // the fall itself, beyond the linear range
    if (x.t < 2.0 * kWindow) continue;  // the start-up nutation (Re -8.5 1/s) still in the window
    const double frozen = spinning_stability(scene.model, SpinningState::upright, x.spin).max_real;
    EXPECT_GT(x.rate, frozen) << "t = " << x.t << ", spin " << x.spin;
  }

  // The slow passage's own zero: passage_growth_rate() at the run's mean spin-down rate (start to crossing), bisected.
  const auto at_cross = std::find_if(s.begin(), s.end(), [&](const Sample& x) { return x.spin < c.spin; });
  ASSERT_TRUE(at_cross != s.end());
  const double spin_rate = (at_cross->spin - s.front().spin) / (at_cross->t - s.front().t);
  note("mean spin-down rate [rad/s^2]", spin_rate);
  double lo = c.spin, hi = w_start;  // passage rate > 0 at lo, < 0 at hi (asserted)
  ASSERT_GT(passage_growth_rate(scene.model, SpinningState::upright, lo, spin_rate), 0.0);
  ASSERT_LT(passage_growth_rate(scene.model, SpinningState::upright, hi, spin_rate), 0.0);
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (passage_growth_rate(scene.model, SpinningState::upright, mid, spin_rate) > 0.0 ? lo : hi) = mid;
  }
  note("passage zero of the growth rate [rad/s]", lo);
  note("simulated / passage zero - 1", w_sim / lo - 1.0);
  // 3 %: the window pair spans 0.7 rad/s of spin (0.9 %), and the measured rate is a difference of window peaks.
  EXPECT_NEAR(w_sim / lo, 1.0, 0.03);
  double worst = 0.0;
  for (const WindowRate& x : r) {
    if (x.spin < c.spin || x.t < 2.0 * kWindow) continue;  // the slow part only / not the start-up nutation
    const double predicted = passage_growth_rate(scene.model, SpinningState::upright, x.spin, spin_rate);
    worst = std::max(worst, std::abs(x.rate - predicted));
  }
  note("largest |measured - passage rate| above the critical spin [1/s]", worst);
  EXPECT_LT(worst, 5e-4);  // measured 1.3e-4 against rates of 1e-3 to 4e-3 1/s; the window peaks' jitter

  // The slow passage: from the spin crossing the tool's critical spin to the tilt reaching kFallTilt.
  const auto cross = std::find_if(s.begin(), s.end(), [&](const Sample& x) { return x.spin < c.spin; });
  const auto fall = std::find_if(s.begin(), s.end(), [](const Sample& x) { return x.tilt > kFallTilt; });
  ASSERT_TRUE(cross != s.end() && fall != s.end());
  const double delay = fall->t - cross->t;
  note("t at the critical spin [s]", cross->t);
  note("t at tilt 0.5 [s]", fall->t);
  note("delay of the visible fall [s]", delay);
  EXPECT_GT(delay, 0.0);

  // Quasi-static estimate: tilt(t) = tilt(t0) exp(int Re lambda_max(spin(t)) dt) with the tool's largest real part
  // at the simulated spin, from a table over the spin range of the run (linear interpolation).
  const int table = 400;
  const double w_lo = std::min(s.back().spin, c.spin) * 0.9, w_hi = w_start * 1.01;
  std::vector<double> lam(table + 1), pass(table + 1);
  for (int i = 0; i <= table; ++i) {
    const double w = w_lo + (w_hi - w_lo) * i / table;
    lam[i] = spinning_stability(scene.model, SpinningState::upright, w).max_real;
    pass[i] = passage_growth_rate(scene.model, SpinningState::upright, w, spin_rate);
  }
  auto interpolate = [&](const std::vector<double>& v, double w) {
    const double x = std::clamp((w - w_lo) / (w_hi - w_lo) * table, 0.0, double(table) - 1e-9);
    const int i = int(x);
    return v[i] + (v[i + 1] - v[i]) * (x - i);
  };
  auto rate = [&](double w) { return interpolate(lam, w); };
  // (a) from the start, the tilt's whole history (after the first window: the fast modes have died); (b) the naive
  // one: the tilt at the crossing taken as the initial tilt (no memory of the decay above the critical spin).
  const double t_a0 = kWindow;
  double log_tilt = std::log(std::max_element(s.begin(), s.begin() + int(kWindow / kSample),
                                              [](const Sample& a, const Sample& b) { return a.tilt < b.tilt; })->tilt);
  double t_pred = NAN, t_naive = NAN, log_naive = std::log(s.front().tilt), min_log = log_tilt;
  double log_pass = log_tilt, min_pass = log_tilt, t_pass = NAN;  // (c) with the passage rate
  for (std::size_t i = 1; i < s.size(); ++i) {
    const double dt = s[i].t - s[i - 1].t, l = rate(0.5 * (s[i].spin + s[i - 1].spin));
    if (s[i].t > t_a0) log_tilt += l * dt;
    if (s[i].t > t_a0) log_pass += interpolate(pass, 0.5 * (s[i].spin + s[i - 1].spin)) * dt;
    min_pass = std::min(min_pass, log_pass);
    if (std::isnan(t_pass) && log_pass > std::log(kFallTilt)) t_pass = s[i].t;
    min_log = std::min(min_log, log_tilt);
    if (std::isnan(t_pred) && log_tilt > std::log(kFallTilt)) t_pred = s[i].t;
    if (s[i].t >= cross->t) log_naive += l * dt;
    if (std::isnan(t_naive) && log_naive > std::log(kFallTilt)) t_naive = s[i].t;
  }
  note("quasi-static predicted t at tilt 0.5 [s]", t_pred);
  note("quasi-static predicted delay [s]", t_pred - cross->t);
  note("predicted smallest tilt [rad]", std::exp(min_log));
  note("passage-rate predicted t at tilt 0.5 [s]", t_pass);
  note("passage-rate predicted smallest tilt [rad]", std::exp(min_pass));
  note("naive delay (tilt at crossing = initial tilt) [s]", t_naive - cross->t);
  double sim_min = INFINITY;
  for (const Sample& x : s) sim_min = std::min(sim_min, x.tilt);
  note("simulated smallest tilt [rad]", sim_min);
}

// The lag is the patch's own: a smaller patch slows the spin-down (M_n ~ mu N Rbar) and the tilt's growth and decay
// alike, so the passage is no more quasi-static. With a fixed patch of 0.3 times the Hertz radius (and the tilt
// scaled with Rbar, the linear range) the tilt turns to growth at the same spin as with the Hertz patch.
TEST(WakeUp, ASmallerPatchWakesAtTheSameSpin) {
  Scene scene = load_scene(top_sim_test::scene_path("spin_down"));
  FiniteContact& fc = scene.model.finite_contact;
  const double a_hertz = patch_radius(fc, scene.model.top.tip_radius, scene.model.top.mass * scene.model.plane.gravity);
  auto wake_spin = [](const Scene& sc, double scale) {
    Simulator sim(sc);
    const std::vector<Sample> s = run(sim, sc.duration);
    EXPECT_EQ(sim.end_state(), EndState::fallen) << "t = " << sim.time();
    return sign_change_spin(window_rates(s, kWindow / scale));
  };
  const double w_hertz = wake_spin(scene, 1.0);
  const double scale = 0.3;
  fc.hertz = false;
  fc.patch_radius = scale * a_hertz;
  scene.initial.tilt *= scale;
  scene.duration /= scale;
  const double critical = locate_critical_spin(scene.model, SpinningState::upright, 0.0, 1.0, scene.initial.spin, 200).spin;
  const double w_small = wake_spin(scene, scale);
  note("patch radius, Hertz / smaller [m]", a_hertz);
  note("sign change, Hertz patch [rad/s]", w_hertz);
  note("sign change, 0.3 x patch [rad/s]", w_small);
  note("critical spin, 0.3 x patch [rad/s]", critical);
  EXPECT_NEAR(w_small / w_hertz, 1.0, 0.01);  // measured 79.25 and 79.26 rad/s
  EXPECT_GT(w_small / critical, 1.2);          // still about 26 % above the frozen critical spin
}

}  // namespace
