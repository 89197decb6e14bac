// Contact shapes (physics.md section 13): the lowest point of a sphere and of a rim, its kinematics, and one shape's
// motion: the tip sphere's against dynamics.cpp, a rolling disc's steady motion against Omega^2 a sin(beta) = 4 g.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "test_util.hpp"
#include "top_sim/contact_shapes.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "../../src/core/shape_motion.hpp"

namespace {

using top_sim::ContactMode;
using top_sim::ContactShape;
using top_sim::ShapeKind;
using Eigen::Vector3d;

Vector3d tilted_axis(double theta, double azimuth) {
  return {std::sin(theta) * std::cos(azimuth), std::sin(theta) * std::sin(azimuth), std::cos(theta)};
}

// The rim's lowest point by brute force: the least height over its circle, sampled and refined by golden section.
double rim_lowest_height(const ContactShape& rim, const Vector3d& f_hat) {
  const Vector3d a = f_hat.unitOrthogonal(), b = f_hat.cross(a);
  auto z = [&](double phi) { return rim.offset * f_hat.z() + rim.radius * (std::cos(phi) * a.z() + std::sin(phi) * b.z()); };
  double best = 0.0;
  for (int i = 0; i < 3600; ++i)
    if (z(i * 2 * M_PI / 3600) < z(best)) best = i * 2 * M_PI / 3600;
  double lo = best - 2 * M_PI / 3600, hi = best + 2 * M_PI / 3600;
  for (int i = 0; i < 100; ++i) {
    const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    (z(m1) < z(m2) ? hi : lo) = z(m1) < z(m2) ? m2 : m1;
  }
  return z(0.5 * (lo + hi));
}

TEST(ContactShapes, RimLowestPointIsTheCirclesLeastHeight) {
  const ContactShape rim{ShapeKind::rim, 0.004, 0.02};
  for (double theta : {0.05, 0.4, 1.2, 2.0, 3.0}) {
    const Vector3d f_hat = tilted_axis(theta, 0.7);
    const top_sim::ShapePoint p = top_sim::shape_point(rim, f_hat, Vector3d::Zero());
    EXPECT_NEAR(p.height, rim_lowest_height(rim, f_hat), 1e-12) << "theta " << theta;
    EXPECT_NEAR(p.r.z(), p.height, 1e-15);
    EXPECT_NEAR((p.r - rim.offset * f_hat).norm(), rim.radius, 1e-15);  // on the rim
    EXPECT_NEAR((p.r - rim.offset * f_hat).dot(f_hat), 0.0, 1e-15);      // in its plane
  }
}

// r_k' against central differences of r_k along the exact rotation of f_hat at a constant w.
TEST(ContactShapes, ContactPointRateMatchesDifferences) {
  const Vector3d w(3.0, -2.0, 40.0);
  for (const ContactShape& shape : {ContactShape{ShapeKind::rim, 0.004, 0.02}, ContactShape{ShapeKind::sphere, -0.01, 1.5e-3}}) {
    const Vector3d f_hat = tilted_axis(0.6, 0.3);
    const double h = 1e-6;
    auto r_at = [&](double t) {
      const Vector3d f = Eigen::AngleAxisd(w.norm() * t, w.normalized()) * f_hat;
      return top_sim::shape_point(shape, f, w).r;
    };
    const Vector3d difference = (r_at(h) - r_at(-h)) / (2 * h);
    const top_sim::ShapePoint p = top_sim::shape_point(shape, f_hat, w);
    EXPECT_LT((p.r_rate - difference).norm(), 1e-7 * p.r_rate.norm()) << top_sim::to_string(shape.kind);
    // h' c' = n . (w x r_k): the contact point is the lowest, so its material normal velocity is the gap's rate.
    EXPECT_NEAR(p.height_slope * w.cross(f_hat).z(), w.cross(p.r).z(), 1e-12 * w.norm() * p.r.norm());
  }
}

// A top of tip sphere and crown rim touches with its tip upright and with its crown past the angle where the two
// lowest points are level: -f c - R = d c - rho s, tan-form solved by bisection here.
TEST(ContactShapes, LowestShapeHandsOverWhereTheHeightsAreLevel) {
  top_sim::ShapeSet body;
  body.shape[0] = {ShapeKind::sphere, -0.010, 1.5e-3};
  body.shape[1] = {ShapeKind::rim, 0.004, 0.02};
  body.count = 2;
  auto difference = [&](double theta) {
    return top_sim::shape_height(body.shape[1], std::cos(theta)) - top_sim::shape_height(body.shape[0], std::cos(theta));
  };
  double lo = 0.0, hi = M_PI / 2;
  for (int i = 0; i < 200; ++i) (difference(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double level = 0.5 * (lo + hi);  // about 0.97 rad for these sizes
  EXPECT_GT(level, 0.5);
  EXPECT_LT(level, 1.4);
  EXPECT_EQ(top_sim::lowest_shape(body, tilted_axis(level - 1e-6, 0.2)), 0u);
  EXPECT_EQ(top_sim::lowest_shape(body, tilted_axis(level + 1e-6, 0.2)), 1u);
  EXPECT_EQ(top_sim::lowest_shape(body, tilted_axis(0.0, 0.0)), 0u);
}

}  // namespace

namespace {

// The body's state in centre-of-mass form, as a shape's motion sees it.
struct Body {
  Vector3d r_cm, v_cm, f_hat, w;
  double w_diss = 0.0;
};

// One classical RK4 step of a body touching with `shape` in `mode` (the test's own integrator: fixed steps).
void rk4_step(const top_sim::Model& model, const ContactShape& shape, ContactMode mode, Body& y, double h) {
  struct Rate { Vector3d r, v, f, w; double diss; };
  auto rate = [&](const Body& b) {
    const top_sim::ShapeMotion m = top_sim::shape_motion(model, shape, mode, b.v_cm, b.f_hat.normalized(), b.w);
    return Rate{b.v_cm, m.a_cm, b.w.cross(b.f_hat), m.omega_dot, m.dissipation};
  };
  auto plus = [](const Body& b, const Rate& k, double s) {
    return Body{b.r_cm + s * k.r, b.v_cm + s * k.v, b.f_hat + s * k.f, b.w + s * k.w, b.w_diss + s * k.diss};
  };
  const Rate k1 = rate(y), k2 = rate(plus(y, k1, h / 2)), k3 = rate(plus(y, k2, h / 2)), k4 = rate(plus(y, k3, h));
  y.r_cm += h / 6 * (k1.r + 2 * k2.r + 2 * k3.r + k4.r);
  y.v_cm += h / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v);
  y.f_hat += h / 6 * (k1.f + 2 * k2.f + 2 * k3.f + k4.f);
  y.w += h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w);
  y.w_diss += h / 6 * (k1.diss + 2 * k2.diss + 2 * k3.diss + k4.diss);
  y.f_hat.normalize();
}

// A nutating, sliding state of a top: tilted 0.3 rad, 150 rad/s about its figure axis and a transverse part, its
// tip sliding at 3 cm/s.
struct SlidingState {
  top_sim::StateVector y{};
  Vector3d f_hat, w, v_cm;
};
SlidingState sliding_state(const top_sim::Model& model) {
  SlidingState st;
  st.f_hat = tilted_axis(0.3, 0.4);
  top_sim::set_figure_axis(st.y, st.f_hat);
  top_sim::set_angular_velocity(st.y, 150.0 * st.f_hat + Vector3d(2.0, -1.0, 0.5));
  top_sim::set_velocity(st.y, Eigen::Vector2d(0.03, -0.01));
  st.w = top_sim::angular_velocity(st.y);
  st.v_cm = top_sim::velocity3(st.y) + model.top.com_offset * st.w.cross(st.f_hat);
  return st;
}

// The tip sphere's motion is the one dynamics.cpp integrates: same force, accelerations and slip at a nutating,
// sliding state of the default top, slipping and rolling.
TEST(ShapeMotion, TipSphereAgreesWithTheRightHandSide) {
  const top_sim::Scene scene = top_sim_test::scene_from(top_sim_test::standard_scene(0.1, 150.0));
  const top_sim::Model& model = scene.model;
  const SlidingState st = sliding_state(model);
  const top_sim::StateVector& y = st.y;
  const Vector3d &f_hat = st.f_hat, &w = st.w, &v_cm = st.v_cm;
  for (ContactMode mode : {ContactMode::slipping, ContactMode::rolling}) {
    top_sim::Dynamics expected;
    top_sim::evaluate_dynamics(model, mode, y, expected);
    const top_sim::ShapeMotion m = top_sim::shape_motion(model, top_sim::tip_sphere(model.top), mode, v_cm, f_hat, w);
    const char* name = top_sim::to_string(mode);
    EXPECT_LT((m.force - expected.contact_force).norm(), 1e-12 * expected.contact_force.norm()) << name;
    EXPECT_LT((m.a_cm - expected.a_cm).norm(), 1e-12 * (expected.a_cm.norm() + 9.81)) << name;
    EXPECT_LT((m.omega_dot - expected.omega_dot).norm(), 1e-12 * expected.omega_dot.norm()) << name;
    EXPECT_NEAR(m.normal_force, expected.normal_force, 1e-12 * expected.normal_force) << name;
    EXPECT_NEAR(m.mu, expected.mu, 1e-12) << name;
    EXPECT_NEAR(m.dissipation, expected.dissipation, 1e-12 * std::abs(expected.dissipation) + 1e-15) << name;
    if (mode == ContactMode::slipping) {
      EXPECT_NEAR(m.slip, expected.contact.slip, 1e-13);
      EXPECT_NEAR(m.painleve, expected.margins.painleve, 1e-12 * std::abs(expected.margins.painleve));
    }
  }
}

// On a patch (physics.md section 12) the tip sphere's slipping motion is still the one dynamics.cpp integrates: the
// coupled sliding and drilling law, the Hertz radius from N (two passes), air and rolling resistance; each law and
// pressure, at a state where drilling and sliding are both large (a omega_n / |v_t| ~ 0.5).
TEST(ShapeMotion, TipSphereOnAPatchAgreesWithTheRightHandSide) {
  for (const char* contact : {"{patch_radius: hertz, rolling_resistance: 1e-5}",
                              "{patch_radius: hertz, drilling_law: elliptic}",
                              "{patch_radius: 2.0e-4, patch_pressure: uniform, rolling_resistance: 1e-5}"}) {
    const top_sim::Scene scene = top_sim_test::scene_from(
        std::string("top: aluminium\nplane: {inclination: 0.1}\nfriction: pmma\ncontact: ") + contact +
        "\nair: {spin_drag: 1.0e-7, drag: 1.0e-3}\ninitial: {start: tilted, tilt: 0.1, spin: 150.0}\n");
    const top_sim::Model& model = scene.model;
    const SlidingState st = sliding_state(model);
    const top_sim::StateVector& y = st.y;
    const Vector3d &f_hat = st.f_hat, &w = st.w, &v_cm = st.v_cm;
    top_sim::Dynamics expected;
    top_sim::evaluate_dynamics(model, ContactMode::slipping, y, expected);
    const top_sim::ShapeMotion m =
        top_sim::shape_motion(model, top_sim::tip_sphere(model.top), ContactMode::slipping, v_cm, f_hat, w);
    ASSERT_GT(std::abs(expected.drilling_torque), 1e-3 * expected.normal_force * expected.patch_radius) << contact;
    EXPECT_LT((m.force - expected.contact_force).norm(), 1e-12 * expected.contact_force.norm()) << contact;
    EXPECT_LT((m.a_cm - expected.a_cm).norm(), 1e-12 * (expected.a_cm.norm() + 9.81)) << contact;
    EXPECT_LT((m.omega_dot - expected.omega_dot).norm(), 1e-12 * expected.omega_dot.norm()) << contact;
    EXPECT_NEAR(m.normal_force, expected.normal_force, 1e-12 * expected.normal_force) << contact;
    EXPECT_NEAR(m.mu, expected.mu, 1e-12) << contact;
    EXPECT_NEAR(m.slip, expected.contact.slip, 1e-13) << contact;
    EXPECT_NEAR(m.patch_radius, expected.patch_radius, 1e-12 * expected.patch_radius) << contact;
    EXPECT_NEAR(m.drilling_torque, expected.drilling_torque, 1e-12 * std::abs(expected.drilling_torque)) << contact;
    EXPECT_NEAR(m.dissipation, expected.dissipation, 1e-12 * std::abs(expected.dissipation)) << contact;
    EXPECT_NEAR(m.painleve, expected.margins.painleve, 1e-12 * std::abs(expected.margins.painleve)) << contact;
    // Stuck on the patch (pivoting too): F and M_n keep v_c and omega_n constant, as stick_force_finite's.
    top_sim::Dynamics stuck;
    top_sim::evaluate_dynamics(model, ContactMode::rolling, y, stuck);
    const top_sim::ShapeMotion r =
        top_sim::shape_motion(model, top_sim::tip_sphere(model.top), ContactMode::rolling, v_cm, f_hat, w);
    ASSERT_GT(std::abs(stuck.drilling_torque), 0.0) << contact;
    EXPECT_LT((r.force - stuck.contact_force).norm(), 1e-11 * stuck.contact_force.norm()) << contact;
    EXPECT_LT((r.omega_dot - stuck.omega_dot).norm(), 1e-11 * stuck.omega_dot.norm()) << contact;
    EXPECT_NEAR(r.drilling_torque, stuck.drilling_torque, 1e-11 * std::abs(stuck.drilling_torque)) << contact;
    EXPECT_NEAR(r.dissipation, stuck.dissipation, 1e-11 * std::abs(stuck.dissipation) + 1e-15) << contact;
  }
}

// physics.md section 12's closed form on a body of shapes: top_life's upright top pivoting in place on its tip's
// Hertz patch loses spin at (mu(s) m g Rbar + k omega) / I_f, s = Rbar omega / (Rbar omega + v_eps) (pure pivoting),
// Rbar = 3 pi a / 16, a = (3 m g R / (4 E*))^(1/3).
TEST(ShapeMotion, UprightTopOnItsHertzPatchSpinsDownAtTheClosedFormRate) {
  const top_sim::Scene scene = top_sim::load_scene(top_sim_test::scene_path("top_life"));
  const top_sim::Model& model = scene.model;
  const double omega = 100.0, mg = model.top.mass * 9.81, I_f = model.top.inertia_axial;
  const top_sim::ShapeMotion m = top_sim::shape_motion(model, model.shapes.shape[0], ContactMode::slipping,
                                                       Vector3d::Zero(), Vector3d::UnitZ(), omega * Vector3d::UnitZ());
  const double a = std::cbrt(3.0 * mg * 1.5e-3 / (4.0 * model.finite_contact.effective_modulus));
  const double lever = 3.0 * M_PI / 16.0 * a;
  const double mu = top_sim::friction_coefficient(model.friction, lever * omega / (lever * omega + model.regularization_speed));
  EXPECT_NEAR(m.normal_force, mg, 1e-12 * mg);
  EXPECT_NEAR(m.patch_radius, a, 1e-12 * a);
  EXPECT_NEAR(m.drilling_torque, -mu * mg * lever, 1e-9 * mu * mg * lever);
  const double rate = -(mu * mg * lever + model.air.spin_drag * omega) / I_f;
  EXPECT_NEAR(m.omega_dot.z(), rate, 1e-9 * std::abs(rate));
  EXPECT_LT(m.omega_dot.head<2>().norm(), 1e-12 * std::abs(rate));
  EXPECT_NEAR(m.dissipation, -rate * I_f * omega, 1e-9 * std::abs(rate) * I_f * omega);
}

// A thin disc (mass 0.4 kg, radius a = 0.04 m: I_d = m a^2 / 4, I_f = m a^2 / 2) rolling on a level plane.
top_sim::Model thin_disc() {
  top_sim::Model model;
  model.top.mass = 0.4;
  model.top.inertia_transverse = 0.4 * 0.04 * 0.04 / 4;
  model.top.inertia_axial = 0.4 * 0.04 * 0.04 / 2;
  model.plane = top_sim::make_plane(0.0, 9.81);
  model.friction.kind = top_sim::FrictionLawKind::coulomb;
  model.friction.mu = 0.3;
  return model;
}

// The disc at beta to the plane, its centre at rest on the lowest point's vertical, turning at w = Omega (n - c f):
// w is parallel to the contact radius, so the contact's material velocity is 0 and the contact circles at Omega.
Body rolling_disc_start(double beta, double Omega) {
  const Vector3d f_hat(-std::sin(beta), 0.0, std::cos(beta)), n = Vector3d::UnitZ();
  return Body{Vector3d(0.0, 0.0, 0.04 * std::sin(beta)), Vector3d::Zero(), f_hat, Omega * (n - f_hat.z() * f_hat)};
}

struct RollingRun {
  double beta_drift = 0.0, max_centre_speed = 0.0, max_gap = 0.0, max_energy_change = 0.0, max_contact_speed = 0.0;
};

RollingRun roll(const top_sim::Model& model, double beta, double Omega, double T, double h) {
  const ContactShape rim{ShapeKind::rim, 0.0, 0.04};
  Body y = rolling_disc_start(beta, Omega);
  const double E0 = top_sim::shape_body_energy(model, y.r_cm, y.v_cm, y.f_hat, y.w);
  RollingRun run;
  for (int k = 0; k < static_cast<int>(std::lround(T / h)); ++k) {
    rk4_step(model, rim, ContactMode::rolling, y, h);
    const top_sim::ShapePoint p = top_sim::shape_point(rim, y.f_hat, y.w);
    run.beta_drift = std::max(run.beta_drift, std::abs(std::acos(y.f_hat.z()) - beta));
    run.max_centre_speed = std::max(run.max_centre_speed, y.v_cm.norm());
    run.max_gap = std::max(run.max_gap, std::abs(y.r_cm.z() + p.height));
    run.max_contact_speed = std::max(run.max_contact_speed, (y.v_cm + y.w.cross(p.r)).norm());
    const double E = top_sim::shape_body_energy(model, y.r_cm, y.v_cm, y.f_hat, y.w);
    run.max_energy_change = std::max(run.max_energy_change, std::abs(E - E0) / E0);
  }
  return run;
}

// physics.md section 13: a thin disc rolling with its centre at rest has Omega^2 a sin(beta) = 4 g. Started there
// it stays (beta, the centre at rest, the gap 0, rolling without work); 2 % off that Omega, beta moves.
TEST(ShapeMotion, RollingDiscSteadyStateIsFourGOverASinBeta) {
  const top_sim::Model model = thin_disc();
  for (double beta : {0.2, 0.5, 1.0}) {
    const double Omega = std::sqrt(4 * 9.81 / (0.04 * std::sin(beta)));
    const RollingRun steady = roll(model, beta, Omega, 1.0, 2e-5);
    EXPECT_LT(steady.beta_drift, 1e-9) << "beta " << beta;
    EXPECT_LT(steady.max_centre_speed, 1e-9) << "beta " << beta;
    EXPECT_LT(steady.max_gap, 1e-12) << "beta " << beta;
    EXPECT_LT(steady.max_contact_speed, 1e-10) << "beta " << beta;
    EXPECT_LT(steady.max_energy_change, 1e-10) << "beta " << beta;
    const RollingRun off = roll(model, beta, 1.02 * Omega, 1.0, 2e-5);
    EXPECT_GT(off.beta_drift, 1e-3) << "beta " << beta;
    EXPECT_LT(off.max_gap, 1e-10) << "beta " << beta;          // still on its rim
    EXPECT_LT(off.max_energy_change, 1e-9) << "beta " << beta;  // rolling does no work
  }
}

// A disc rolling on its rim with its centre pushed sideways, so that it slips (Coulomb, mu 0.3): E + W_diss holds,
// the gap stays 0, and friction works.
TEST(ShapeMotion, SlippingRimKeepsTheEnergyBalance) {
  const top_sim::Model model = thin_disc();
  const ContactShape rim{ShapeKind::rim, 0.0, 0.04};
  Body y = rolling_disc_start(0.6, 40.0);
  y.v_cm = Vector3d(0.2, 0.1, 0.0);  // the centre moving: the contact slips
  const double E0 = top_sim::shape_body_energy(model, y.r_cm, y.v_cm, y.f_hat, y.w);
  double max_balance = 0.0, max_gap = 0.0, min_normal = 1e9, min_slip_speed = 1e9;
  for (int k = 0; k < 4000; ++k) {  // 0.04 s: it sticks at about 0.045 s (the Simulator's mode switch, not RK4's)
    rk4_step(model, rim, ContactMode::slipping, y, 1e-5);
    const top_sim::ShapeMotion m = top_sim::shape_motion(model, rim, ContactMode::slipping, y.v_cm, y.f_hat, y.w);
    min_normal = std::min(min_normal, m.normal_force);
    min_slip_speed = std::min(min_slip_speed, m.v_t.norm());
    const double E = top_sim::shape_body_energy(model, y.r_cm, y.v_cm, y.f_hat, y.w);
    max_balance = std::max(max_balance, std::abs(E + y.w_diss - E0) / E0);
    max_gap = std::max(max_gap, std::abs(y.r_cm.z() + top_sim::shape_height(rim, y.f_hat.z())));
  }
  EXPECT_GT(min_normal, 0.0);              // it stayed in contact
  EXPECT_GT(min_slip_speed, 0.03);         // and slipping (v_t from 0.22 m/s)
  EXPECT_GT(y.w_diss, 1e-3 * E0);          // friction worked
  EXPECT_LT(max_balance, 1e-10);
  EXPECT_LT(max_gap, 1e-10);
}

}  // namespace

namespace {

// The aluminium top of the default scene with a crown rim (radius 20 mm, 4 mm above the centre of mass), lying on
// its tip and crown: the tilt where both lowest points are level.
struct FallenTop {
  std::array<ContactShape, 2> shapes{ContactShape{ShapeKind::sphere, -0.010, 1.5e-3}, ContactShape{ShapeKind::rim, 0.004, 0.02}};
  double tilt = 0.0;
  Vector3d f_hat;
};
FallenTop fallen_top() {
  FallenTop top;
  auto difference = [&](double theta) {
    return top_sim::shape_height(top.shapes[1], std::cos(theta)) - top_sim::shape_height(top.shapes[0], std::cos(theta));
  };
  double lo = 0.0, hi = M_PI / 2;
  for (int i = 0; i < 200; ++i) (difference(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  top.tilt = 0.5 * (lo + hi);
  top.f_hat = tilted_axis(top.tilt, 0.0);
  return top;
}

top_sim::Model aluminium_top(double inclination) {
  top_sim::Model model;  // m 0.025 kg, I_f 5e-6, I_d 3e-6 kg m^2
  model.plane = top_sim::make_plane(inclination, 9.81);
  model.friction.kind = top_sim::FrictionLawKind::coulomb;
  model.friction.mu = 0.3;
  return model;
}

// At rest on tip and crown on a level plane, both stuck: the normal forces of the lever rule about the centre of
// mass, N_1 x_1 + N_2 x_2 = 0 and N_1 + N_2 = m g (x_k the contacts' horizontal offsets), and no friction.
TEST(TwoShapeMotion, FallenTopAtRestCarriesItsWeightByTheLeverRule) {
  const top_sim::Model model = aluminium_top(0.0);
  const FallenTop top = fallen_top();
  const top_sim::TwoShapeMotion m = top_sim::two_shape_motion(model, top.shapes, {ContactMode::rolling, ContactMode::rolling},
                                                              Vector3d::Zero(), top.f_hat, Vector3d::Zero());
  const double x1 = top_sim::shape_point(top.shapes[0], top.f_hat, Vector3d::Zero()).r.x();
  const double x2 = top_sim::shape_point(top.shapes[1], top.f_hat, Vector3d::Zero()).r.x();
  const double mg = model.top.mass * 9.81;
  ASSERT_LT(x1 * x2, 0.0);  // the centre of mass between the contacts
  EXPECT_NEAR(m.normal_force[0], mg * x2 / (x2 - x1), 1e-12 * mg);
  EXPECT_NEAR(m.normal_force[1], -mg * x1 / (x2 - x1), 1e-12 * mg);
  EXPECT_LT(m.force[0].head<2>().norm() + m.force[1].head<2>().norm(), 1e-12 * mg);
  EXPECT_LT(m.a_cm.norm(), 1e-12 * 9.81);
  EXPECT_LT(m.omega_dot.norm(), 1e-9);
}

// Two contacts: integrate the body's centre-of-mass form in the given modes, return the worst balance and gaps.
struct TwoContactRun {
  double max_balance = 0.0, max_gap = 0.0, min_normal = 1e9, dissipated = 0.0;
};
TwoContactRun slide_on_two(const top_sim::Model& model, const FallenTop& top, std::array<ContactMode, 2> modes,
                           Body y, int steps, double h) {
  struct Rate { Vector3d r, v, f, w; double diss; };
  auto rate = [&](const Body& b) {
    const top_sim::TwoShapeMotion m = top_sim::two_shape_motion(model, top.shapes, modes, b.v_cm, b.f_hat.normalized(), b.w);
    return Rate{b.v_cm, m.a_cm, b.w.cross(b.f_hat), m.omega_dot, m.dissipation};
  };
  auto plus = [](const Body& b, const Rate& k, double s) {
    return Body{b.r_cm + s * k.r, b.v_cm + s * k.v, b.f_hat + s * k.f, b.w + s * k.w, b.w_diss + s * k.diss};
  };
  const double E0 = top_sim::shape_body_energy(model, y.r_cm, y.v_cm, y.f_hat, y.w);
  TwoContactRun run;
  for (int i = 0; i < steps; ++i) {
    const Rate k1 = rate(y), k2 = rate(plus(y, k1, h / 2)), k3 = rate(plus(y, k2, h / 2)), k4 = rate(plus(y, k3, h));
    const Rate sum{k1.r + 2 * k2.r + 2 * k3.r + k4.r, k1.v + 2 * k2.v + 2 * k3.v + k4.v,
                   k1.f + 2 * k2.f + 2 * k3.f + k4.f, k1.w + 2 * k2.w + 2 * k3.w + k4.w,
                   k1.diss + 2 * k2.diss + 2 * k3.diss + k4.diss};
    y = plus(y, sum, h / 6);
    y.f_hat.normalize();
    const top_sim::TwoShapeMotion m = top_sim::two_shape_motion(model, top.shapes, modes, y.v_cm, y.f_hat, y.w);
    run.min_normal = std::min({run.min_normal, m.normal_force[0], m.normal_force[1]});
    const double E = top_sim::shape_body_energy(model, y.r_cm, y.v_cm, y.f_hat, y.w);
    run.max_balance = std::max(run.max_balance, std::abs(E + y.w_diss - E0) / E0);
    for (const ContactShape& shape : top.shapes)
      run.max_gap = std::max(run.max_gap, std::abs(y.r_cm.z() + top_sim::shape_height(shape, y.f_hat.z())));
  }
  run.dissipated = y.w_diss / E0;
  return run;
}

// The fallen top sliding and turning about the vertical on tip and crown (both slipping), and with the tip stuck
// while the crown slips: E + W_diss holds, both gaps stay 0, both normal forces stay positive.
TEST(TwoShapeMotion, SlidingOnTipAndCrownKeepsTheBalanceAndBothGaps) {
  const top_sim::Model model = aluminium_top(0.0);
  const FallenTop top = fallen_top();
  const double z_cm = -top_sim::shape_height(top.shapes[0], top.f_hat.z());
  // w along n and v_cm in-plane keep both contacts' normal velocities 0.
  const Body start{Vector3d(0.0, 0.0, z_cm), Vector3d(0.15, 0.05, 0.0), top.f_hat, Vector3d(0.0, 0.0, 6.0)};
  const TwoContactRun both = slide_on_two(model, top, {ContactMode::slipping, ContactMode::slipping}, start, 2000, 1e-5);
  EXPECT_GT(both.min_normal, 0.0);
  EXPECT_GT(both.dissipated, 1e-3);
  EXPECT_LT(both.max_balance, 1e-10);
  EXPECT_LT(both.max_gap, 1e-11);
  // The tip stuck at rest needs a start whose tip does not move: turning about the vertical through it.
  const Vector3d r_tip = top_sim::shape_point(top.shapes[0], top.f_hat, Vector3d::Zero()).r;
  const Vector3d w(0.0, 0.0, 6.0);
  const Body pivoting{Vector3d(0.0, 0.0, z_cm), -w.cross(r_tip), top.f_hat, w};
  const TwoContactRun mixed = slide_on_two(model, top, {ContactMode::rolling, ContactMode::slipping}, pivoting, 2000, 1e-5);
  EXPECT_GT(mixed.min_normal, 0.0);
  EXPECT_GT(mixed.dissipated, 1e-3);
  EXPECT_LT(mixed.max_balance, 1e-10);
  EXPECT_LT(mixed.max_gap, 1e-11);
}

// The fallen top turning about the vertical on tip and crown with a patch at each (physics.md sections 12-13): both
// slip, each with its own coupled sliding and drilling law. A Hertz patch sizes the tip's from its N; the crown's
// sharp edge has none. A given patch radius drills at both. E + W_diss holds, the gaps stay 0, N_k > 0, and the
// patches take more than the point contacts do.
TEST(TwoShapeMotion, SlidingOnTipAndCrownOnPatchesKeepsTheBalance) {
  top_sim::Model model = aluminium_top(0.0);
  model.friction.kind = top_sim::FrictionLawKind::paper;  // mu(0) = 0: a patch on shapes slips
  const FallenTop top = fallen_top();
  const double z_cm = -top_sim::shape_height(top.shapes[0], top.f_hat.z());
  const Body start{Vector3d(0.0, 0.0, z_cm), Vector3d(0.15, 0.05, 0.0), top.f_hat, Vector3d(0.0, 0.0, 6.0)};
  const TwoContactRun point = slide_on_two(model, top, {ContactMode::slipping, ContactMode::slipping}, start, 2000, 1e-5);
  top_sim::Material aluminium{6.9e10, 0.33}, pmma{3.0e9, 0.37};
  model.finite_contact.hertz = true;
  model.finite_contact.effective_modulus = top_sim::effective_modulus(aluminium, pmma);
  const top_sim::TwoShapeMotion m = top_sim::two_shape_motion(model, top.shapes, {ContactMode::slipping, ContactMode::slipping},
                                                              start.v_cm, start.f_hat, start.w);
  // Sized by the N of a first pass as point contacts (one fixed-point step, as the tip sphere's): within 1e-3.
  EXPECT_NEAR(m.patch_radius[0], top_sim::hertz_patch_radius(model.finite_contact, 1.5e-3, m.normal_force[0]),
              1e-3 * m.patch_radius[0]);
  EXPECT_EQ(m.patch_radius[1], 0.0);  // the crown's edge
  EXPECT_LT(m.drilling_torque[0] * start.w.z(), 0.0);
  EXPECT_EQ(m.drilling_torque[1], 0.0);
  const TwoContactRun hertz = slide_on_two(model, top, {ContactMode::slipping, ContactMode::slipping}, start, 2000, 1e-5);
  model.finite_contact.hertz = false;
  model.finite_contact.patch_radius = 5.0e-4;
  const top_sim::TwoShapeMotion fixed = top_sim::two_shape_motion(
      model, top.shapes, {ContactMode::slipping, ContactMode::slipping}, start.v_cm, start.f_hat, start.w);
  EXPECT_LT(fixed.drilling_torque[0] * start.w.z(), 0.0);
  EXPECT_LT(fixed.drilling_torque[1] * start.w.z(), 0.0);
  const TwoContactRun given = slide_on_two(model, top, {ContactMode::slipping, ContactMode::slipping}, start, 2000, 1e-5);
  for (const TwoContactRun& run : {hertz, given}) {
    EXPECT_GT(run.min_normal, 0.0);
    EXPECT_GT(run.dissipated, point.dissipated);
    EXPECT_LT(run.max_balance, 1e-10);
    EXPECT_LT(run.max_gap, 1e-11);
  }
  EXPECT_GT(given.dissipated, hertz.dissipated);  // 0.5 mm at both against ~0.1 mm at the tip alone
}

}  // namespace
