// The finite contact of physics.md section 12 against its closed forms and invariants.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.hpp"
#include "../../src/core/angular_momentum.hpp"
#include "top_sim/dynamics.hpp"
#include "../../src/core/energy.hpp"
#include "top_sim/finite_contact.hpp"
#include "../../src/core/exact_law_table.hpp"

using namespace top_sim;
using top_sim_test::num;
using top_sim_test::scene_from;

namespace {

// The exact law's force and torque (units mu N and mu N Rbar) at a omega_n / |v_t| = ratio, through the table.
PatchIntegrals law_through_table(PatchPressure p, double ratio) {
  const double lever = drilling_lever(p, 1.0);
  const double theta = std::atan(ratio * lever);
  const DrillingFactors k = drilling_factors(DrillingLaw::exact, p, 1.0, ratio * lever);
  return {k.force * std::cos(theta), k.torque * std::sin(theta)};
}

std::vector<double> ratios() {
  std::vector<double> r;
  for (double e = -3.0; e <= 3.0001; e += 0.05) r.push_back(std::pow(10.0, e));
  return r;
}

}  // namespace

TEST(PatchIntegrals, PureSlidingAndPurePivotingAreTheLawsEnds) {
  for (PatchPressure p : {PatchPressure::hertz, PatchPressure::uniform}) {
    const PatchIntegrals slide = patch_integrals(p, 0.0);
    EXPECT_EQ(slide.force, 1.0);
    EXPECT_EQ(slide.torque, 0.0);
    const PatchIntegrals pivot = patch_integrals(p, INFINITY);
    EXPECT_NEAR(pivot.force, 0.0, 1e-12) << to_string(p);
    EXPECT_NEAR(pivot.torque, 1.0, 1e-6) << to_string(p) << ": M_n = mu N Rbar, Rbar = 3 pi a / 16 or 2 a / 3";
  }
}

// The compiled tables (exact_law_table.cpp, generated) are the quadrature's: regenerate them with
// top_sim_exact_law_table when patch_integrals() changes.
TEST(ExactDrillingLaw, CompiledTablesAreTheQuadratures) {
  for (PatchPressure p : {PatchPressure::hertz, PatchPressure::uniform}) {
    const exact_law::Table fresh = exact_law::compute(p);
    const exact_law::Table& compiled = exact_law::table(p);
    double worst = 0.0;
    for (int i = 0; i + 1 < exact_law::kNodes; ++i)
      for (int k = 0; k < 4; ++k)
        worst = std::max({worst, std::abs(fresh.interval[i].force[k] - compiled.interval[i].force[k]),
                          std::abs(fresh.interval[i].torque[k] - compiled.interval[i].torque[k])});
    for (int i = 0; i < exact_law::kNodes; ++i)
      worst = std::max({worst, std::abs(fresh.surface_force[i] - compiled.surface_force[i]),
                        std::abs(fresh.surface_torque[i] - compiled.surface_torque[i])});
    EXPECT_LT(worst, 1e-12) << to_string(p);
  }
}

// The patch radius's cube root against the library's: two Halley steps reach 1e-14.
TEST(HertzPatch, CubeRootAgreesWithCbrt) {
  double worst = 0.0;
  for (double e = -30.0; e <= 10.0; e += 0.013) {
    const double x = std::pow(10.0, e);
    worst = std::max(worst, std::abs(cube_root(x) / std::cbrt(x) - 1.0));
  }
  EXPECT_LT(worst, 1e-14);
}

// The table's law against the patch integrals by a finer, independent quadrature: within 1 % of mu N and of
// mu N Rbar at every ratio from 1e-3 to 1e3 (physics.md section 12).
TEST(ExactDrillingLaw, WithinOnePercentOfThePatchIntegralsAtEveryRatio) {
  for (PatchPressure p : {PatchPressure::hertz, PatchPressure::uniform}) {
    double worst_f = 0.0, worst_g = 0.0;
    for (double r : ratios()) {
      const PatchIntegrals ref = patch_integrals(p, r, 6000), law = law_through_table(p, r);
      worst_f = std::max(worst_f, std::abs(law.force - ref.force));
      worst_g = std::max(worst_g, std::abs(law.torque - ref.torque));
    }
    EXPECT_LT(worst_f, 0.01) << to_string(p);
    EXPECT_LT(worst_g, 0.01) << to_string(p);
    std::cout << to_string(p) << ": largest error " << worst_f << " mu N (force), " << worst_g
              << " mu N Rbar (torque)\n";
  }
}

// Where drilling dominates, the Hertz patch's force is F ~ 1.18 mu N |v_t| / (a omega_n), and the elliptic law's
// is 44 % larger (physics.md section 12).
TEST(ExactDrillingLaw, DrillingDominatedForceAndTheEllipticLawsExcess) {
  const double r = 1000.0;
  const PatchIntegrals ref = patch_integrals(PatchPressure::hertz, r, 6000);
  EXPECT_NEAR(ref.force * r, 1.18, 0.01);
  const double lever = drilling_lever(PatchPressure::hertz, 1.0), theta = std::atan(r * lever);
  const double elliptic = std::cos(theta);  // F / (mu N) of the elliptic law
  EXPECT_NEAR(elliptic / ref.force, 1.44, 0.02);
}

TEST(StickSet, EllipsoidAndLimitSurfaceBounds) {
  const double mu = 0.3, N = 2.0, lever = 1e-4;
  // Inside, on and outside the ellipsoid.
  EXPECT_GT(stick_margin(DrillingLaw::elliptic, PatchPressure::hertz, 0.3, 0.3 * mu * N * lever, mu, N, lever), 0.0);
  EXPECT_NEAR(stick_margin(DrillingLaw::elliptic, PatchPressure::hertz, 0.6 * mu * N, 0.8 * mu * N * lever, mu, N, lever),
              0.0, 1e-12);
  EXPECT_LT(stick_margin(DrillingLaw::elliptic, PatchPressure::hertz, 0.7 * mu * N, 0.8 * mu * N * lever, mu, N, lever), 0.0);
  // The exact law's surface passes through its own (f, g) at every ratio.
  for (double r : {0.1, 1.0, 10.0}) {
    const PatchIntegrals I = law_through_table(PatchPressure::hertz, r);
    EXPECT_NEAR(stick_margin(DrillingLaw::exact, PatchPressure::hertz, I.force * mu * N, I.torque * mu * N * lever, mu,
                             N, lever),
                0.0, 1e-3 * mu * N);
  }
}

namespace {

// An upright top spinning on a level plane with Coulomb friction: only the drilling torque (or air) acts.
std::string upright_scene(double spin, const std::string& contact, const std::string& extra = "",
                          const std::string& friction = "{law: coulomb, mu: 0.3}") {
  return "top: aluminium\n"
         "plane: {inclination: 0.0}\n"
         "friction: " + friction + "\n"
         "contact: {" + contact + "}\n" + extra +
         "initial: {start: tilted, tilt: 0.0, spin: " + num(spin) + "}\n"
         "integrator: {method: dopri5, rtol: 1.0e-10, atol: 1.0e-12}\n";
}

}  // namespace

// physics.md section 12: an upright top pivoting in place with Coulomb mu loses spin at mu m g Rbar / I_f.
TEST(FiniteContact, UprightTopPivotingLosesSpinAtTheClosedFormRate) {
  for (const char* law : {"exact", "elliptic"}) {
    for (const char* pressure : {"hertz", "uniform"}) {
      const double a = 2.0e-4;
      Scene scene = scene_from(upright_scene(100.0, std::string("patch_radius: ") + num(a) + ", drilling_law: " + law +
                                                        ", patch_pressure: " + pressure));
      Simulator sim(scene);
      ASSERT_TRUE(sim.advance_to(1.0));
      const Top& top = scene.model.top;
      const double lever = std::string(pressure) == "hertz" ? 3 * M_PI * a / 16 : 2 * a / 3;
      const double rate = 0.3 * top.mass * 9.81 * lever / top.inertia_axial;
      const Snapshot s = sim.snapshot();
      EXPECT_NEAR(s.spin, 100.0 - rate * 1.0, 1e-6 * 100.0) << law << " " << pressure;
      EXPECT_NEAR(s.drilling_torque, -0.3 * top.mass * 9.81 * lever, 1e-9) << law << " " << pressure;
      EXPECT_DOUBLE_EQ(s.patch_radius, a);
    }
  }
}

// The Hertz patch from the two materials: a = (3 N R / (4 E*))^(1/3) with N = m g on a level plane.
TEST(FiniteContact, HertzPatchFromTheMaterials) {
  Scene scene = scene_from(
      "top: {mass: 0.025, tip_radius: 1.5e-3, com_offset: 0.01, inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6,\n"
      "      young_modulus: 7.0e10, poisson_ratio: 0.33}\n"
      "plane: {inclination: 0.0}\n"
      "friction: {law: coulomb, mu: 0.3, young_modulus: 3.0e9, poisson_ratio: 0.37}\n"
      "contact: {patch_radius: hertz}\n"
      "initial: {start: tilted, tilt: 0.0, spin: 100.0}\n");
  const double E = 1.0 / ((1 - 0.33 * 0.33) / 7.0e10 + (1 - 0.37 * 0.37) / 3.0e9);
  const double a = std::cbrt(3.0 * 0.025 * 9.81 * 1.5e-3 / (4.0 * E));
  Simulator sim(scene);
  ASSERT_TRUE(sim.advance_to(0.1));
  EXPECT_NEAR(sim.snapshot().patch_radius, a, 1e-12);
  const double rate = 0.3 * 0.025 * 9.81 * 3 * M_PI * a / 16 / 5.0e-6;
  EXPECT_NEAR(sim.snapshot().spin, 100.0 - 0.1 * rate, 1e-6);
}

// physics.md section 12: with air spin drag alone the spin decays as exp(-k t / I_f).
TEST(FiniteContact, AirSpinDragDecaysTheSpinExponentially) {
  const double k = 2.0e-7;
  Scene scene = scene_from(upright_scene(100.0, "", "air: {spin_drag: " + num(k) + "}\n"));
  Simulator sim(scene);
  ASSERT_TRUE(sim.advance_to(2.0));
  EXPECT_NEAR(sim.snapshot().spin, 100.0 * std::exp(-k * 2.0 / scene.model.top.inertia_axial), 1e-7 * 100.0);
}

// A ball rolling on a level plane with rolling resistance delta: v' = -delta m g R / (I + m R^2) while it rolls.
TEST(FiniteContact, RollingResistanceDeceleratesARollingBall) {
  const double R = 0.01, m = 0.1, I = 4.0e-6, v0 = 0.5, delta = 1.0e-4;
  Scene scene = scene_from(
      "top: {mass: 0.1, tip_radius: 0.01, com_offset: 0.0, inertia_axial: 4.0e-6, inertia_transverse: 4.0e-6}\n"
      "plane: {inclination: 0.0}\n"
      "friction: {law: coulomb, mu: 0.2, static: 0.3}\n"
      "contact: {rolling_resistance: " + num(delta) + "}\n"
      "initial: {start: tilted, tilt: 0.0, spin: 0.0, velocity: [" + num(v0) + ", 0.0],"
      " angular_velocity_transverse: [0.0, " + num(v0 / R) + "]}\n"
      "integrator: {method: dopri5, rtol: 1.0e-10, atol: 1.0e-12}\n");
  Simulator sim(scene);
  ASSERT_TRUE(sim.advance_to(1.0));
  const Snapshot s = sim.snapshot();
  EXPECT_EQ(s.contact_mode, ContactMode::rolling);
  const double decel = delta * m * 9.81 * R / (I + m * R * R);
  EXPECT_NEAR(s.com_velocity.x(), v0 - decel * 1.0, 1e-6);
  EXPECT_NEAR(s.dissipated_work, 0.5 * (m + I / (R * R)) * (v0 * v0 - std::pow(v0 - decel, 2)), 1e-9);
}

// A pivoting patch that runs out of spin sticks (physics.md section 12: a contact may stick in pivoting).
TEST(FiniteContact, PivotingPatchSticksWhenItsSpinRunsOut) {
  Scene scene = scene_from(upright_scene(2.0, "patch_radius: 2.0e-4", "", "{law: coulomb, mu: 0.3, static: 0.35}"));
  const double rate = 0.3 * 0.025 * 9.81 * 3 * M_PI * 2.0e-4 / 16 / 5.0e-6;
  Simulator sim(scene);
  ASSERT_TRUE(sim.advance_to(2.0 / rate + 0.5));
  const Snapshot s = sim.snapshot();
  EXPECT_EQ(s.contact_mode, ContactMode::rolling);
  EXPECT_NEAR(s.spin, 0.0, 1e-5);
  EXPECT_EQ(s.drilling_torque, s.drilling_torque);  // finite
  EXPECT_NEAR(s.drilling_torque, 0.0, 1e-12) << "nothing left to resist";
}

namespace {

// A nutating top on an incline with every section-12 term.
Scene every_term_scene(const std::string& law) {
  return scene_from(
      "top: {mass: 0.025, tip_radius: 1.5e-3, com_offset: 0.01, inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6,\n"
      "      young_modulus: 7.0e10, poisson_ratio: 0.33}\n"
      "plane: {inclination: 0.1}\n"
      "friction: {law: paper, mu_c: 0.25, s_c: 0.6, young_modulus: 3.0e9, poisson_ratio: 0.37}\n"
      "contact: {patch_radius: hertz, drilling_law: " + law + ", rolling_resistance: 2.0e-5}\n"
      "air: {spin_drag: 1.0e-8, drag: 1.0e-3}\n"
      "initial: {start: tilted, tilt: 0.2, spin: 150.0}\n"
      "integrator: {method: dopri5, rtol: 1.0e-10, atol: 1.0e-12}\n");
}

}  // namespace

// Every term dissipates and is booked: E + W_diss stays E(0) (physics.md sections 9 and 12).
TEST(FiniteContact, EnergyBalanceHoldsWithEveryTerm) {
  for (const char* law : {"exact", "elliptic"}) {
    Scene scene = every_term_scene(law);
    Simulator sim(scene);
    const double e0 = mechanical_energy(scene.model, sim.state());
    ASSERT_TRUE(sim.advance_to(1.0));
    const Snapshot s = sim.snapshot();
    EXPECT_GT(s.dissipated_work, 1e-5) << law;
    EXPECT_NEAR(s.energy + s.dissipated_work, e0, 1e-8 * e0) << law;
    EXPECT_LT(s.spin, 150.0) << law << ": the top spins down";
  }
}

// Jellett's lambda = L . (f f_hat + R n) changes at (couple + air torque) . (f f_hat + R n); on a point contact
// without air it is conserved. Checked at states along a run, with d lambda / dt from the right-hand side.
TEST(FiniteContact, JellettRateUnderTheDrillingTorque) {
  for (bool finite : {false, true}) {
    Scene scene = finite ? every_term_scene("exact") : scene_from(top_sim_test::standard_scene(0.1, 150.0));
    Simulator sim(scene);
    for (int k = 1; k <= 5; ++k) {
      ASSERT_TRUE(sim.advance_to(0.1 * k));
      const StateVector& y = sim.state();
      StateVector dydt;
      derivative(scene.model, sim.snapshot().contact_mode, y, dydt);
      const double h = 1e-7;
      StateVector yp = y, ym = y;
      for (int i = 0; i < static_cast<int>(idx::size); ++i) {
        yp[i] += h * dydt[i];
        ym[i] -= h * dydt[i];
      }
      const double numeric = (jellett(scene.model, yp) - jellett(scene.model, ym)) / (2 * h);
      Dynamics dyn;
      evaluate_dynamics(scene.model, sim.snapshot().contact_mode, y, dyn);
      const Eigen::Vector3d arm = scene.model.top.com_offset * figure_axis(y).normalized() +
                                  Eigen::Vector3d(0, 0, scene.model.top.tip_radius);
      const double rate = (dyn.couple + dyn.air_torque).dot(arm);
      const double scale = std::abs(jellett(scene.model, y));
      if (finite) {
        EXPECT_LT(rate, 0.0) << "the drilling torque drains lambda";
        EXPECT_NEAR(numeric, rate, 1e-4 * std::abs(rate) + 1e-9 * scale) << "t = " << sim.time();
      } else {
        EXPECT_EQ(rate, 0.0);
        EXPECT_NEAR(numeric, 0.0, 1e-6 * scale) << "t = " << sim.time();
      }
    }
  }
}

TEST(FiniteContactScene, BadInputNamesKeyValueAndRange) {
  const auto error = [](const std::string& yaml) {
    try {
      scene_from(yaml);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string base = "top: aluminium\nfriction: pmma\n";
  EXPECT_NE(error(base + "contact: {patch_radius: -1.0e-4}").find("contact.patch_radius: -1e-04 is out of range; must be in [0, 1] [m], or hertz"), std::string::npos);
  EXPECT_NE(error(base + "contact: {patch_radius: .nan}").find("contact.patch_radius"), std::string::npos);
  // A top without its material (the shipped tops and planes carry theirs).
  EXPECT_NE(error("top: {mass: 0.025}\nfriction: pmma\ncontact: {patch_radius: hertz}")
                .find("contact.patch_radius: 'hertz' needs both materials: top.young_modulus and top.poisson_ratio (given: no)"),
            std::string::npos);
  EXPECT_EQ(error(base + "contact: {patch_radius: hertz}"), "accepted");
  EXPECT_NE(error("top: {young_modulus: 7.0e10, poisson_ratio: 0.6}\n").find("top.poisson_ratio: 0.6 is out of range; must be in (-1, 0.5]"), std::string::npos);
  EXPECT_NE(error("top: {young_modulus: 7.0e10}\n").find("top.poisson_ratio: required"), std::string::npos);
  EXPECT_NE(error(base + "contact: {rolling_resistance: -1}").find("contact.rolling_resistance: -1 is out of range; must be >= 0"), std::string::npos);
  EXPECT_NE(error(base + "air: {drag: -1}").find("air.drag: -1 is out of range; must be >= 0"), std::string::npos);
  EXPECT_NE(error(base + "air: {spin_drag: inf}").find("air.spin_drag"), std::string::npos);
  EXPECT_NE(error(base + "contact: {drilling_law: ellipse}").find("contact.drilling_law: 'ellipse' is not one of exact | elliptic"), std::string::npos);
  // The reduced model carries a patch and air spin drag (physics.md section 12.1), not rolling resistance or drag.
  EXPECT_EQ(error(base + "model: {kind: adiabatic}\ncontact: {patch_radius: 1.0e-4}\nair: {spin_drag: 1.0e-9}"), "accepted");
  EXPECT_NE(error(base + "model: {kind: auto}\ncontact: {rolling_resistance: 1.0e-5}")
                .find("contact.rolling_resistance: 0 with model.kind auto (the reduced model of physics.md section 7 "
                      "carries a patch and air spin drag, not rolling resistance or air drag); use model.kind: full"),
            std::string::npos);
  EXPECT_NE(error(base + "model: {kind: adiabatic}\nair: {drag: 1.0e-6}").find("air.drag: 0 with model.kind adiabatic"),
            std::string::npos);
}

TEST(FiniteContactCommand, RefusedValuesLeaveTheModel) {
  Scene scene = scene_from(top_sim_test::standard_scene(0.1, 150.0));
  Command c;
  c.patch_radius = -1.0;
  EXPECT_EQ(validate(c, scene.model), "patch_radius = -1: must be in [0, 1] m");
  c = Command{};
  c.drag = NAN;
  EXPECT_NE(validate(c, scene.model).find("drag = nan"), std::string::npos);
  c = Command{};
  c.spin_drag = 1e-8;
  c.rolling_resistance = 1e-5;
  c.patch_radius = 1e-4;
  EXPECT_EQ(validate(c, scene.model), "");
  Simulator sim(scene);
  sim.submit(c);
  ASSERT_TRUE(sim.advance_to(0.01));
  EXPECT_EQ(sim.snapshot().patch_radius, 1e-4);
}

// Zero terms take the point contact's path: the default scene is the same to the bit with the keys given as 0.
TEST(FiniteContact, ZeroTermsAreThePointContactToTheBit) {
  Scene point = scene_from(top_sim_test::standard_scene(0.1, 150.0));
  Scene zeros = scene_from(top_sim_test::standard_scene(0.1, 150.0) +
                           "contact: {patch_radius: 0.0, rolling_resistance: 0.0}\nair: {spin_drag: 0.0, drag: 0.0}\n");
  Simulator a(point), b(zeros);
  ASSERT_TRUE(a.advance_to(0.5));
  ASSERT_TRUE(b.advance_to(0.5));
  for (int i = 0; i < static_cast<int>(idx::size); ++i) EXPECT_EQ(a.state()[i], b.state()[i]) << i;
}
