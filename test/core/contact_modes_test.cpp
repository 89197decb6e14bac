// Contact modes of physics.md section 9: the ball's analytic checks, impacts, the hopping and rolling tops,
// event detection, stick-speed convergence, and the Coulomb law at the default regularisation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "test_util.hpp"
#include "top_sim/dynamics.hpp"
#include "../../src/core/energy.hpp"

namespace {

using namespace top_sim;
using top_sim_test::num;
using top_sim_test::scene_from;

constexpr double kG = 9.81;

// A homogeneous ball (f = 0, I_f = I_d = 2/5 m R^2): m 0.1 kg, R 1 cm.
const double kBallMass = 0.1, kBallRadius = 0.01, kBallInertia = 0.4 * 0.1 * 0.01 * 0.01;

std::string ball_scene(double alpha, const std::string& friction, const std::string& initial,
                       const std::string& extra = "") {
  return "top: {mass: " + num(kBallMass) + ", tip_radius: " + num(kBallRadius) +
         ", com_offset: 0.0, inertia_axial: " + num(kBallInertia) + ", inertia_transverse: " + num(kBallInertia) +
         "}\nplane: {inclination: " + num(alpha) + ", gravity: " + num(kG) + "}\nfriction: " + friction +
         "\ninitial: " + initial + "\n" + extra;
}

std::vector<ModeSwitch> switches_of(Simulator& sim, double t_end) {
  sim.advance_to(t_end);
  return sim.take_mode_switches();
}

int count(const std::vector<ModeSwitch>& v, ModeSwitchKind kind) {
  return static_cast<int>(std::count_if(v.begin(), v.end(), [kind](const ModeSwitch& m) { return m.kind == kind; }));
}

// ---- the ball (physics.md section 9, analytic checks) ---------------------------------------------------------

TEST(Ball, SlidingOnALevelCoulombPlaneRollsFromTStarAtFiveSeventhsOfV0) {
  const double mu = 0.2, v0 = 1.0;
  Simulator sim(scene_from(ball_scene(0.0, "{law: coulomb, mu: " + num(mu) + "}", "{tilt: 0.0, spin: 0.0, velocity: [1.0, 0.0]}")));
  ASSERT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_EQ(sim.contact_mode(), ContactMode::slipping);
  const double e0 = sim.snapshot().energy;
  const auto sw = switches_of(sim, 1.0);
  ASSERT_EQ(sw.size(), 1u);
  EXPECT_EQ(sw[0].kind, ModeSwitchKind::stick);
  EXPECT_EQ(sw[0].to, ContactMode::rolling);
  // The stick fires at |v_t| = v_stick = 1e-6 m/s, which the slip reaches v_stick / (7/2 mu g) = 1.5e-7 s early.
  const double t_star = 2.0 * v0 / (7.0 * mu * kG);
  EXPECT_NEAR(sw[0].t, t_star, 3e-7);
  EXPECT_LE(sw[0].t, t_star);
  const Snapshot s = sim.snapshot();
  EXPECT_EQ(s.contact_mode, ContactMode::rolling);
  // The stick impulse removes the last v_t along the slip direction: the rolling speed is exact to rounding.
  EXPECT_NEAR(s.tip_velocity.x(), 5.0 * v0 / 7.0, 1e-12);
  EXPECT_NEAR(s.tip_velocity.y(), 0.0, 1e-12);
  // Rolling without slipping: u = R omega x n.
  EXPECT_NEAR(s.angular_velocity.y(), s.tip_velocity.x() / kBallRadius, 1e-9);
  // Lost: m v0^2 / 7 (slip work plus the stick impulse), booked in W_diss.
  EXPECT_NEAR(e0 - s.energy, kBallMass * v0 * v0 / 7.0, 1e-12);
  EXPECT_NEAR(s.dissipated_work, kBallMass * v0 * v0 / 7.0, 1e-12);
  EXPECT_LT(sim.max_energy_residual(), 1e-12);
  top_sim_test::note("ball: t_stick - t*", sw[0].t - t_star);
}

TEST(Ball, OnAnInclineRollsIfTanAlphaIsAtMostSevenHalvesMuElseSlides) {
  const double mu = 0.2;  // 7/2 mu = 0.7: atan(0.7) = 0.6107 rad
  for (double alpha : {0.3, 0.55, 0.65, 0.8}) {
    SCOPED_TRACE("alpha = " + num(alpha));
    Simulator sim(scene_from(ball_scene(alpha, "{law: coulomb, mu: " + num(mu) + "}", "{tilt: 0.0, spin: 0.0}")));
    const bool rolls = std::tan(alpha) <= 3.5 * mu;
    EXPECT_EQ(sim.contact_mode(), rolls ? ContactMode::rolling : ContactMode::slipping);
    const double T = 0.5;
    const auto sw = switches_of(sim, T);
    EXPECT_TRUE(sw.empty()) << sw.size() << " switches, first " << to_string(sw[0].kind);
    const double a = rolls ? 5.0 / 7.0 * kG * std::sin(alpha) : kG * (std::sin(alpha) - mu * std::cos(alpha));
    const Snapshot s = sim.snapshot();
    EXPECT_NEAR(-s.tip_velocity.y(), a * T, 1e-9 * a * T);  // downhill is -y
    EXPECT_NEAR(-s.contact_point.y(), 0.5 * a * T * T, 1e-9 * a * T * T);
    EXPECT_NEAR(s.tip_velocity.x(), 0.0, 1e-12);
    if (rolls) {
      EXPECT_LE(s.mu, mu * (1.0 + 1e-12));  // the mobilised friction 2/7 tan(alpha) stays within mu_s
    }
  }
}

TEST(Ball, DroppedFromGapHTouchesDownAtTheFreeFallTimeAndBouncesToENSquaredH) {
  const double alpha = 0.2, h = 0.02, e = 0.8;
  Simulator sim(scene_from(ball_scene(alpha, "{law: coulomb, mu: 0.0}", "{tilt: 0.0, spin: 0.0, gap: " + num(h) + "}",
                                      "contact: {restitution: " + num(e) + "}\n")));
  EXPECT_EQ(sim.contact_mode(), ContactMode::flight);
  const double g_n = kG * std::cos(alpha);
  const double t_drop = std::sqrt(2.0 * h / g_n);
  const auto sw = switches_of(sim, 1.1 * t_drop);
  ASSERT_EQ(sw.size(), 1u) << "first at t = " << sw[0].t << ", " << to_string(sw[0].kind);
  EXPECT_EQ(sw[0].kind, ModeSwitchKind::touchdown);
  EXPECT_EQ(sw[0].to, ContactMode::flight);  // e_N |v_n| = 0.5 m/s > v_settle: it bounces
  EXPECT_NEAR(sw[0].t, t_drop, 1e-9);
  // Frictionless: the impact keeps the in-plane motion, reverses e_N of the normal speed, loses (1 - e^2) of it.
  const double v_n = g_n * t_drop;
  EXPECT_NEAR(sw[0].energy_change, -0.5 * kBallMass * v_n * v_n * (1.0 - e * e), 1e-9 * kBallMass * v_n * v_n);
  // The next apex, e_N v_n / g_n after the impact, is e_N^2 h.
  const double t_apex = sw[0].t + e * v_n / g_n;
  sim.advance_to(t_apex);
  EXPECT_NEAR(sim.snapshot().gap, e * e * h, 1e-8 * h);
  EXPECT_NEAR(sim.state()[idx::gap_rate], 0.0, 1e-8 * v_n);
  EXPECT_LT(sim.max_energy_residual(), 1e-12);
}

TEST(Ball, BouncingEndsAfterFinitelyManyImpactsWithThePlasticSettleRule) {
  // e_N = 0.5 from 2 cm: impacts at ever smaller speeds until e_N |v_n| < v_settle = 1e-5 m/s closes the contact.
  Simulator sim(scene_from(ball_scene(0.0, "{law: coulomb, mu: 0.2}", "{tilt: 0.0, spin: 0.0, gap: 0.02}",
                                      "contact: {restitution: 0.5}\n")));
  const auto sw = switches_of(sim, 1.0);
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  ASSERT_FALSE(sw.empty());
  // Impact speeds fall by e_N each time: 0.63 m/s to 1e-5 m/s takes log(0.63e5 * 0.5) / log 2 + 1 = 16 impacts.
  EXPECT_EQ(count(sw, ModeSwitchKind::touchdown), static_cast<int>(sw.size()));
  EXPECT_GE(sw.size(), 14u);
  EXPECT_LE(sw.size(), 18u);
  EXPECT_NE(sw.back().to, ContactMode::flight);
  EXPECT_EQ(sim.contact_mode(), ContactMode::rolling);  // at rest on a level plane: rolling holds with F_t = 0
  for (const ModeSwitch& m : sw) EXPECT_LE(m.energy_change, 0.0) << "t = " << m.t;
  EXPECT_EQ(sim.snapshot().gap, 0.0);
  EXPECT_LT(sim.max_energy_residual(), 1e-10);
}

// Oblique impacts on a level plane, ball without spin: K_tt = 7/(2m), K_nn = 1/m at the contact, so the sticking
// impulse is admissible iff 2 |v_t| / 7 <= mu (1 + e_N) |v_n|.
struct ImpactCase {
  double v_t, v_n;
};

Snapshot after_impact(double mu, double e, ImpactCase c, ModeSwitch& sw) {
  Simulator sim(scene_from(ball_scene(0.0, "{law: coulomb, mu: " + num(mu) + "}",
                                      "{tilt: 0.0, spin: 0.0, velocity: [" + num(c.v_t) + ", 0.0], gap: 1.0e-12, gap_rate: " +
                                          num(-c.v_n) + "}",
                                      "contact: {restitution: " + num(e) + "}\n")));
  const auto switches = switches_of(sim, 1e-9);  // touchdown after ~1e-11 s; gravity adds ~1e-10 m/s
  EXPECT_EQ(switches.size(), 1u);
  if (!switches.empty()) sw = switches[0];
  return sim.snapshot();
}

TEST(Impact, ObliqueImpactStickingBranch) {
  const double mu = 0.3, e = 0.5;
  const ImpactCase c{0.5, 1.0};  // 2/7 * 0.5 = 0.143 <= 0.3 * 1.5 * 1 = 0.45: sticks
  ModeSwitch sw;
  const Snapshot s = after_impact(mu, e, c, sw);
  EXPECT_EQ(sw.kind, ModeSwitchKind::touchdown);
  EXPECT_EQ(s.contact_mode, ContactMode::flight);  // it bounces at e_N v_n
  EXPECT_NEAR(s.tip_velocity.z(), e * c.v_n, 1e-6);
  EXPECT_NEAR(s.tip_velocity.x(), 5.0 / 7.0 * c.v_t, 1e-9);          // the contact point stops sliding
  EXPECT_NEAR(s.tip_velocity.x() - kBallRadius * s.angular_velocity.y(), 0.0, 1e-9);
  EXPECT_LT(sw.energy_change, 0.0);
}

TEST(Impact, ObliqueImpactSlidingBranch) {
  const double mu = 0.3, e = 0.5;
  const ImpactCase c{1.0, 0.2};  // 2/7 = 0.286 > 0.3 * 1.5 * 0.2 = 0.09: slides through the impact
  ModeSwitch sw;
  const Snapshot s = after_impact(mu, e, c, sw);
  EXPECT_EQ(s.contact_mode, ContactMode::flight);
  const double P_n = (1.0 + e) * kBallMass * c.v_n;
  EXPECT_NEAR(s.tip_velocity.z(), e * c.v_n, 1e-6);
  EXPECT_NEAR(s.tip_velocity.x(), c.v_t - mu * P_n / kBallMass, 1e-9);
  EXPECT_NEAR(s.angular_velocity.y(), kBallRadius * mu * P_n / kBallInertia, 1e-6);
  EXPECT_LT(sw.energy_change, 0.0);
}

TEST(Impact, PlasticImpactClosesTheContactAtZeroNormalSpeed) {
  ModeSwitch sw;
  const Snapshot s = after_impact(0.3, 0.0, ImpactCase{0.5, 1.0}, sw);
  EXPECT_NE(s.contact_mode, ContactMode::flight);
  EXPECT_EQ(s.gap, 0.0);
  EXPECT_EQ(s.tip_velocity.z(), 0.0);
}

// ---- tops -----------------------------------------------------------------------------------------------------

TEST(RollingTop, ConservesEnergyAndKeepsTheFrictionInsideTheCone) {
  const Scene scene = load_scene(top_sim_test::scene_path("coulomb"));
  Simulator sim(scene);
  const double mu_s = static_friction(scene.model);
  ASSERT_EQ(mu_s, 0.3);
  double e_ref = NAN, worst = 0.0, worst_cone = -1.0, scale = energy_scale(sim.model(), sim.state());
  int rolling_samples = 0;
  std::uint64_t switches = sim.mode_switch_count();
  for (int k = 1; k <= 1000; ++k) {
    sim.advance_to(5e-3 * k);
    const Snapshot s = sim.snapshot();
    ASSERT_EQ(s.fault, ContactFault::none) << s.fault_message;
    if (sim.mode_switch_count() != switches) {  // a new rolling phase starts a new energy reference
      switches = sim.mode_switch_count();
      e_ref = NAN;
    }
    if (s.contact_mode != ContactMode::rolling) continue;
    ++rolling_samples;
    if (std::isnan(e_ref)) e_ref = s.energy;
    worst = std::max(worst, std::abs(s.energy - e_ref) / scale);
    EXPECT_GT(s.normal_force, 0.0);
    worst_cone = std::max(worst_cone, s.friction_force.norm() - mu_s * s.normal_force);
  }
  EXPECT_GT(rolling_samples, 900);
  EXPECT_LT(worst, 1e-9);  // physics.md: rolling does no work
  EXPECT_LE(worst_cone, 1e-12);
  top_sim_test::note("rolling top: max |E - E0| / scale over rolling phases", worst);
}

Scene hopping_scene(const std::string& extra = "") {
  Scene scene = load_scene(top_sim_test::scene_path("hopping"));
  if (!extra.empty()) scene = scene_from(std::string("top: aluminium\nplane: {inclination: 0.1}\nfriction: pmma\n"
                                                     "contact: {restitution: 0.5}\n"
                                                     "initial: {start: tilted, tilt: 0.1, spin: 5000.0}\n") + extra);
  return scene;
}

TEST(HoppingTop, FiveThousandRadPerSecondHopsHundredsOfTimesWithTheBalanceHeld) {
  Simulator sim(hopping_scene());
  const top_sim_test::CheckedRun r = top_sim_test::run_checked(sim, 0.5, 1000.0);
  EXPECT_EQ(r.nonfinite, "");
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  EXPECT_NEAR(r.result.sim_seconds, 0.5, 1e-12);
  const auto& sw = r.result.mode_switches;
  const int hops = count(sw, ModeSwitchKind::lift_off);
  EXPECT_GE(hops, 100);
  ASSERT_FALSE(sw.empty());
  // physics.md section 9: first lift-off at 0.037 s, a 76 us hop.
  EXPECT_EQ(sw[0].kind, ModeSwitchKind::lift_off);
  EXPECT_NEAR(sw[0].t, 0.037, 0.5e-3);
  ASSERT_GE(sw.size(), 2u);
  EXPECT_EQ(sw[1].kind, ModeSwitchKind::touchdown);
  EXPECT_NEAR(sw[1].t - sw[0].t, 76e-6, 4e-6);
  const double scale = energy_scale(sim.model(), sim.state());
  for (const ModeSwitch& m : sw) EXPECT_LE(m.energy_change, 1e-15 * scale) << to_string(m.kind) << " at " << m.t;
  EXPECT_LT(r.result.max_energy_residual, 1e-8);  // E + W_diss across every mode and impact
  top_sim_test::note("5000 rad/s, 0.5 s: lift-offs", hops);
  top_sim_test::note("5000 rad/s, 0.5 s: touchdowns", count(sw, ModeSwitchKind::touchdown));
  top_sim_test::note("5000 rad/s: first lift-off [s]", sw[0].t);
  top_sim_test::note("5000 rad/s: first hop [s]", sw[1].t - sw[0].t);
  top_sim_test::note("5000 rad/s, 0.5 s: E + W_diss residual", r.result.max_energy_residual);
}

// Event sampling inside steps (physics.md section 9): the same mode switches as a reference whose steps are
// capped at 2 us, far below every hop, where a sign change between steps cannot be missed. The bouncing is
// chaotic (two capped references, 2 us and 0.2 us, part after ~80 switches), so the first 44 switches (up to
// 0.0416 s) are compared. The loose rosenbrock4 run takes ~55 us steps on average, as long as the hops.
void expect_same_switches(const std::vector<ModeSwitch>& a, const std::vector<ModeSwitch>& ref, std::size_t n,
                          double tol) {
  ASSERT_GE(a.size(), n);
  ASSERT_GE(ref.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(a[i].kind, ref[i].kind) << i << " at t = " << ref[i].t;
    EXPECT_NEAR(a[i].t, ref[i].t, tol) << i << ": " << to_string(ref[i].kind);
  }
}

TEST(HoppingTop, EventSamplingMissesNoShortHop) {
  const double T = 0.0417;
  Simulator capped(hopping_scene("integrator: {method: dopri5, max_dt: 2.0e-6}\n"));
  Simulator fast(hopping_scene());
  Simulator loose(hopping_scene("integrator: {method: rosenbrock4, rtol: 1.0e-5, atol: 1.0e-8}\n"));
  const auto ref = switches_of(capped, T), a = switches_of(fast, T), b = switches_of(loose, T);
  EXPECT_EQ(count(ref, ModeSwitchKind::lift_off), 7);
  expect_same_switches(a, ref, 44, 1e-7);
  expect_same_switches(b, ref, 44, 5e-6);
  EXPECT_LT(fast.stats().steps * 4, capped.stats().steps);  // the sampled runs take natural steps
  EXPECT_LT(loose.stats().steps * 20, capped.stats().steps);
  top_sim_test::note("0.0417 s of hopping: steps capped / dopri5 / loose rosenbrock4",
                     static_cast<double>(capped.stats().steps));
  top_sim_test::note("  dopri5 steps", static_cast<double>(fast.stats().steps));
  top_sim_test::note("  loose rosenbrock4 steps", static_cast<double>(loose.stats().steps));
}

TEST(HoppingTop, TwoThousandRadPerSecondHopsThenSlips) {
  Simulator sim(scene_from(top_sim_test::standard_scene(0.1, 2000.0)));
  const top_sim_test::CheckedRun r = top_sim_test::run_checked(sim, 1.0, 100.0);
  EXPECT_EQ(r.nonfinite, "");
  ASSERT_EQ(r.result.final.fault, ContactFault::none) << r.result.final.fault_message;
  const auto& sw = r.result.mode_switches;
  EXPECT_GE(count(sw, ModeSwitchKind::lift_off), 1);
  ASSERT_FALSE(sw.empty());
  EXPECT_NEAR(sw[0].t, 0.085, 2e-3);  // physics.md: first lift-off at 0.085 s
  EXPECT_EQ(r.result.final.contact_mode, ContactMode::slipping);
  EXPECT_LT(sw.back().t, 0.9);  // the hopping is over well before the end
  EXPECT_LT(r.result.max_energy_residual, 1e-8);
  top_sim_test::note("2000 rad/s: lift-offs in 1 s", count(sw, ModeSwitchKind::lift_off));
  top_sim_test::note("2000 rad/s: last switch [s]", sw.back().t);
}

// ---- the stick speed ---------------------------------------------------------------------------------------------

Snapshot coulomb_top_after(double stick_speed, double T) {
  Simulator sim(scene_from("top: aluminium\nplane: {inclination: 0.1}\nfriction: {law: coulomb, mu: 0.3}\n"
                           "initial: {tilt: 0.1, spin: 200.0}\ncontact: {stick_speed: " + num(stick_speed) + "}\n"
                           "integrator: {rtol: 1.0e-11, atol: 1.0e-13}\n"));
  sim.advance_to(T);
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  return sim.snapshot();
}

double state_distance(const Snapshot& a, const Snapshot& b) {
  // Velocities in m/s, the axis and the angular velocity scaled to contact speeds (R omega).
  const double R = 1.5e-3;
  return std::max({(a.tip_velocity - b.tip_velocity).norm(), R * (a.angular_velocity - b.angular_velocity).norm(),
                   (a.contact_point - b.contact_point).norm() / 0.1, (a.figure_axis - b.figure_axis).norm() * R * 200.0});
}

TEST(StickSpeed, FinalStatesConvergeAsTheSquareOfTheStickSpeed) {
  const double T = 0.5;
  const Snapshot s5 = coulomb_top_after(1e-5, T), s6 = coulomb_top_after(1e-6, T), s7 = coulomb_top_after(1e-7, T);
  const double d5 = state_distance(s5, s7), d6 = state_distance(s6, s7);
  top_sim_test::note("stick speed 1e-5 vs 1e-7: state distance [m/s]", d5);
  top_sim_test::note("stick speed 1e-6 vs 1e-7: state distance [m/s]", d6);
  // O(v_stick^2): the stick comes |v_t| / (d|v_t|/dt) early and the impulse removes |v_t|; a velocity scale of
  // 1 m/s makes (1e-5)^2 = 1e-10.
  EXPECT_LT(d5, 1e-9);
  EXPECT_LT(d6, d5);
}

// ---- Coulomb friction at the default regularisation (was DISABLED before the stick model) --------------------------

TEST(CoulombDefault, EveryIntegratorFinishesFiveSecondsAtTheDefaultRegularization) {
  struct Case {
    const char* method;
    double dt;
    std::uint64_t step_budget;
  };
  // Fixed steps at their stability limits for 200 rad/s (docs/performance.md); adaptive ones at default tolerances.
  for (const Case& c : {Case{"dopri5", 1e-4, 20000}, Case{"rosenbrock4", 1e-4, 20000}, Case{"switching", 1e-4, 20000},
                        Case{"rk4", 3e-4, 30000}, Case{"euler", 1e-5, 600000}, Case{"semi_implicit_euler", 1e-5, 600000}}) {
    SCOPED_TRACE(c.method);
    Simulator sim(scene_from(std::string("top: aluminium\nplane: {inclination: 0.1}\nfriction: {law: coulomb, mu: 0.3}\n"
                                         "initial: {tilt: 0.1, spin: 200.0}\nintegrator: {method: ") +
                             c.method + ", dt: " + num(c.dt) + "}\n"));
    ASSERT_EQ(sim.model().regularization_speed, 1e-9);
    for (int k = 1; k <= 50 && sim.stats().steps < c.step_budget && sim.fault() == ContactFault::none; ++k)
      sim.advance_to(0.1 * k);
    EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
    EXPECT_NEAR(sim.time(), 5.0, 1e-9) << "stopped after " << sim.stats().steps << " steps";
    EXPECT_EQ(top_sim_test::nonfinite_fields(sim.snapshot()), "");
    EXPECT_EQ(sim.contact_mode(), ContactMode::rolling);
    top_sim_test::note(std::string("Coulomb 5 s, ") + c.method + ": steps", static_cast<double>(sim.stats().steps));
    top_sim_test::note(std::string("Coulomb 5 s, ") + c.method + ": rosenbrock4 layer steps",
                       static_cast<double>(sim.layer_steps()));
  }
}

// ---- scene keys and commands ---------------------------------------------------------------------------------------

void expect_scene_error(const std::string& yaml, const std::string& key, const std::string& words) {
  try {
    scene_from(yaml);
    ADD_FAILURE() << "accepted: " << yaml;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, key) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ContactKeys, AreValidatedWithFieldValueAndRange) {
  const std::string top = "top: aluminium\n";
  expect_scene_error(top + "friction: {law: coulomb, mu: 0.3, static: 0.2}\n", "friction.static", ">= mu(0) = 0.3");
  expect_scene_error(top + "contact: {restitution: 1.5}\n", "contact.restitution", "in [0, 1]");
  expect_scene_error(top + "contact: {stick_speed: 0}\n", "contact.stick_speed", "> 0");
  expect_scene_error(top + "contact: {settle_speed: -1}\n", "contact.settle_speed", "> 0");
  expect_scene_error(top + "contact: {bounce: 1}\n", "contact.bounce", "unknown key");
  expect_scene_error(top + "friction: {law: paper, static: 0.1}\nmodel: {normal_force: static}\n", "friction.static",
                     "permanent slipping contact");
  expect_scene_error(top + "contact: {restitution: 0.5}\nmodel: {normal_force: static}\n", "contact.restitution",
                     "permanent contact");
  expect_scene_error(top + "initial: {gap: 0.01}\nmodel: {normal_force: static}\n", "initial.gap", "flight start");
  expect_scene_error(top + "initial: {gap_rate: -1.0}\n", "initial.gap_rate", "inside the plane");
  // Defaults: mu_s = mu(0); the static normal force keeps mu_s = 0 even for a Coulomb law.
  EXPECT_EQ(static_friction(scene_from(top + "friction: {law: coulomb, mu: 0.3}\n").model), 0.3);
  EXPECT_EQ(static_friction(scene_from(top + "friction: pmma\n").model), 0.0);
  EXPECT_EQ(static_friction(scene_from(top + "friction: {law: coulomb, mu: 0.3}\nmodel: {normal_force: static}\n").model), 0.0);
  EXPECT_EQ(static_friction(scene_from(top + "friction: {law: paper, static: 0.4}\n").model), 0.4);
  // A ball is a valid top.
  EXPECT_NO_THROW(load_scene(top_sim_test::scene_path("ball")));
}

TEST(ContactCommands, StaticFrictionAndRestitutionAreValidatedAndApplied) {
  Simulator sim(scene_from(top_sim_test::standard_scene(0.1, 200.0)));
  Command bad;
  bad.restitution = 1.5;
  EXPECT_NE(sim.submit(bad).find("restitution = 1.5: must be in [0, 1]"), std::string::npos) << sim.submit(bad);
  Command coulomb;
  coulomb.friction = FrictionChange{};
  coulomb.friction->kind = FrictionLawKind::coulomb;
  coulomb.friction->given.emplace_back(find_friction_parameter("mu"), 0.3);
  coulomb.static_friction = 0.2;
  EXPECT_NE(sim.submit(coulomb).find(">= mu(0) = 0.3"), std::string::npos) << sim.submit(coulomb);
  coulomb.static_friction = 0.35;
  coulomb.restitution = 0.3;
  EXPECT_EQ(sim.submit(coulomb), "");
  sim.advance_to(1.0);
  EXPECT_EQ(sim.model().contact.static_friction.value_or(-1.0), 0.35);
  EXPECT_EQ(sim.model().contact.restitution, 0.3);
  EXPECT_EQ(sim.fault(), ContactFault::none) << sim.fault_message();
  EXPECT_EQ(sim.contact_mode(), ContactMode::rolling);  // the paper top, switched to Coulomb, sticks and rolls
}

}  // namespace
