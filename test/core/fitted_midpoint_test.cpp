// fitted_midpoint against closed forms: an oscillator and a driven oscillator carried exactly at steps longer than
// their period (where the plain rule's phase is 2 atan(h w / 2)), and the frictionless top's nutation kept in phase
// against a tight dopri5 reference at 1.5 nutation periods per step; the angular momentum and the nutation frequency
// it is steered by.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "test_util.hpp"
#include "../../src/core/angular_momentum.hpp"
#include "top_sim/integrators.hpp"
#include "../../src/core/nutation.hpp"
#include "top_sim/plane.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using namespace top_sim;
using top_sim_test::note;

// gap'' = -w^2 gap + c in (gap, gap_rate); every other rate is zero.
System driven_oscillator(double w, double c) {
  return [w, c](const StateVector& y, StateVector& d) {
    d.fill(0.0);
    d[idx::gap] = y[idx::gap_rate];
    d[idx::gap_rate] = -w * w * y[idx::gap] + c;
  };
}

StateVector unit_start() {
  StateVector y{};
  y[idx::f + 2] = 1.0;  // a unit figure axis: the stepper renormalises it
  y[idx::gap] = 1.0;
  return y;
}

// The largest |gap - exact| over n steps of h from gap 1 at rest: exact = c/w^2 + (1 - c/w^2) cos(w t).
double worst_error(Method m, double w, double c, double h, int n) {
  IntegratorSettings s;
  s.method = m;
  s.dt = h;
  std::unique_ptr<Stepper> st = make_stepper(s, driven_oscillator(w, c));
  st->reset(unit_start(), 0.0);
  const double centre = c / (w * w);
  double worst = 0.0;
  for (int k = 1; k <= n; ++k) {
    st->step(std::numeric_limits<double>::infinity());
    worst = std::max(worst, std::abs(st->state()[idx::gap] - (centre + (1.0 - centre) * std::cos(w * k * h))));
  }
  return worst;
}

}  // namespace

// y' = J y + b is carried exactly: at h w = 0.5, 2, 9.8 and 20 (the last two longer than the period) the driven
// oscillator stays on cos(w t) over 300 steps to 1e-6 (the finite-difference J's w^2 is off by ~1e-8, a phase of
// n h w 1e-8 / 2 < 3e-5 rad: the bound holds that 30 times over, with 1e-6 of the amplitude for the rest). The plain
// rule at h w = 9.8 is off by the amplitude itself (its phase per step 2 atan(4.9) = 2.74 rad, not 9.8 - 2 pi = 3.52).
TEST(FittedMidpoint, ADrivenOscillatorIsExactAtStepsLongerThanItsPeriod) {
  const double w = 50.0;
  for (double c : {0.0, 700.0})
    for (double hw : {0.5, 2.0, 9.8, 20.0}) {
      const double e = worst_error(Method::fitted_midpoint, w, c, hw / w, 300);
      note("fitted_midpoint h w = " + std::to_string(hw) + ", drive " + std::to_string(c) + ": largest error", e);
      EXPECT_LT(e, 1e-6 + 300 * hw * 1e-7) << "h w = " << hw << ", c = " << c;
    }
  EXPECT_GT(worst_error(Method::implicit_midpoint, w, 0.0, 9.8 / w, 300), 0.5);
}

namespace {

Scene frictionless(Method m, double dt) { return top_sim_test::frictionless_scene(m, dt, 1e-11); }

double tilt(const StateVector& y) { return std::acos(std::min(1.0, figure_axis(y).normalized().z())); }

// A run against the reference at the run's step ends k dt: the largest contact-point distance over [0, t_end], the
// largest tilt difference over the last half second, and the reference's tilt peak-to-peak there.
struct Comparison {
  double contact = 0.0, tilt = 0.0, reference_tilt_pp = 0.0;
};

Comparison compare(Method m, double dt, double t_end) {
  Simulator run(frictionless(m, dt)), ref(frictionless(Method::dopri5, dt));
  Comparison c;
  double lo = 10.0, hi = -10.0;
  const long n = std::lround(std::floor(t_end / dt));
  for (long k = 1; k <= n; ++k) {
    const double t = static_cast<double>(k) * dt;
    EXPECT_TRUE(run.advance_to(t));
    EXPECT_TRUE(ref.advance_to(t));
    EXPECT_EQ(run.fault(), ContactFault::none) << run.fault_message();
    c.contact = std::max(c.contact, (run.snapshot().contact_point - ref.snapshot().contact_point).head<2>().norm());
    if (t < t_end - 0.5) continue;
    c.tilt = std::max(c.tilt, std::abs(tilt(run.state()) - tilt(ref.state())));
    lo = std::min(lo, tilt(ref.state()));
    hi = std::max(hi, tilt(ref.state()));
  }
  c.reference_tilt_pp = hi - lo;
  return c;
}

}  // namespace

// The frictionless top of bench/peer_mujoco at dt = 3 pi / w (w from the fast-top formula: 1.5 nutation periods per
// step, the midpoint at the nutation's centre), over 2 s against dopri5 at rtol 1e-11 at the step ends: the contact
// point within 0.03 mm (measured 0.0035 mm; the nutation moves it by 0.021 mm peak to peak) and the tilt within 0.3 of
// the nutation's peak-to-peak (measured 0.055: in phase). The plain rule at the same dt has the nutation's frequency
// at 0.30 of the true one: its tilt is out of phase (measured 0.93 of the peak-to-peak; asserted > 0.5).
TEST(FittedMidpoint, KeepsTheFrictionlessTopsNutationInPhaseAtStepsLongerThanItsPeriod) {
  const Scene scene = frictionless(Method::fitted_midpoint, 1.0);
  const double w = fast_top_nutation_frequency(scene.model, initial_state(scene)), dt = 3.0 * M_PI / w;
  note("fast-top nutation frequency [rad/s]", w);
  const Comparison fitted = compare(Method::fitted_midpoint, dt, 2.0);
  note("fitted_midpoint: largest contact-point error [m]", fitted.contact);
  note("fitted_midpoint: largest tilt error over the last 0.5 s / the nutation's peak-to-peak",
       fitted.tilt / fitted.reference_tilt_pp);
  EXPECT_LT(fitted.contact, 3e-5);
  EXPECT_LT(fitted.tilt, 0.3 * fitted.reference_tilt_pp);
  const Comparison plain = compare(Method::implicit_midpoint, dt, 2.0);
  note("implicit_midpoint at that dt: tilt error / the nutation's peak-to-peak", plain.tilt / plain.reference_tilt_pp);
  EXPECT_GT(plain.tilt, 0.5 * plain.reference_tilt_pp);
}

// L = I_f w3 f_hat for a spin about the figure axis, I_d omega for a spin across it, plus J nu f_hat from a rotor.
TEST(AngularMomentum, ClosedFormsOfTheSymmetricTop) {
  Scene scene = load_scene(top_sim_test::scene_path("frictionless"));
  const Top& top = scene.model.top;
  StateVector y{};
  const Eigen::Vector3d f(0.6, 0.0, 0.8), across(0.8, 0.0, -0.6);
  set_figure_axis(y, f);
  set_angular_velocity(y, 200.0 * f);
  EXPECT_LT((angular_momentum(scene.model, y) - top.inertia_axial * 200.0 * f).norm(), 1e-18);
  set_angular_velocity(y, 3.0 * across);
  EXPECT_LT((angular_momentum(scene.model, y) - top.inertia_transverse * 3.0 * across).norm(), 1e-18);
  scene.model.top.has_rotor = true;
  scene.model.top.rotor.inertia_axial = 1e-6;
  y[idx::nu] = 50.0;
  EXPECT_LT((angular_momentum(scene.model, y) - (top.inertia_transverse * 3.0 * across + 1e-6 * 50.0 * f)).norm(),
            1e-18);
}

// On a level frictionless plane the contact force is along the normal and acts at a point on the figure axis's line
// through the tip sphere's centre, so its torque about the centre of mass is horizontal: L . n is conserved. Over
// 2 s of the nutating, precessing top (dopri5 rtol 1e-11) it stays within 1e-12 relative (measured 2e-14). L's
// azimuth turns at the precession's pace without the nutation's wobble: the spread (largest minus smallest) of its
// change per 1 ms is under 10 % of f_hat's, which circles L with the nutation.
TEST(AngularMomentum, ItsNormalPartIsConservedOnALevelFrictionlessPlane) {
  Scene scene = frictionless(Method::dopri5, 1e-4);
  scene.model.plane = make_plane(0.0, scene.model.plane.gravity);
  Simulator sim(scene);
  const Eigen::Vector3d l_start = angular_momentum(sim.model(), sim.state());
  double worst = 0.0, l_az = angular_momentum_azimuth(sim.model(), sim.state());
  double f_az = std::atan2(sim.state()[idx::f + 1], sim.state()[idx::f]);
  double l_lo = 10.0, l_hi = -10.0, f_lo = 10.0, f_hi = -10.0;
  for (int k = 1; k <= 2000; ++k) {
    ASSERT_TRUE(sim.advance_to(1e-3 * k));
    worst = std::max(worst, std::abs(angular_momentum(sim.model(), sim.state()).z() - l_start.z()) / l_start.norm());
    const double la = angular_momentum_azimuth(sim.model(), sim.state());
    const double fa = std::atan2(sim.state()[idx::f + 1], sim.state()[idx::f]);
    const double dl = std::remainder(la - l_az, 2 * M_PI), df = std::remainder(fa - f_az, 2 * M_PI);
    l_lo = std::min(l_lo, dl);
    l_hi = std::max(l_hi, dl);
    f_lo = std::min(f_lo, df);
    f_hi = std::max(f_hi, df);
    l_az = la;
    f_az = fa;
  }
  note("level frictionless plane: largest relative change of L . n over 2 s", worst);
  note("spread of L's azimuth change per ms [rad]", l_hi - l_lo);
  note("spread of f_hat's azimuth change per ms [rad]", f_hi - f_lo);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(l_hi - l_lo, 0.1 * (f_hi - f_lo));
}
