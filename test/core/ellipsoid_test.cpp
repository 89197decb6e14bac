// An ellipsoid's contact geometry (physics.md section 14.1, src/core/ellipsoid.hpp): the sphere as its special case
// (sections 3, 9, 13.1), the lowest point against sampled surfaces, derivatives and curvature against finite
// differences and closed forms, and the acceleration-level terms against an integrated rigid motion.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "top_sim/contact_shapes.hpp"
#include "../../src/core/ellipsoid.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using top_sim::Ellipsoid;

// Deterministic random draws: every run checks the same cases.
struct Draw {
  std::mt19937 gen{48};
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  Vector3d unit() {
    std::normal_distribution<double> g;
    return Vector3d(g(gen), g(gen), g(gen)).normalized();
  }
  Matrix3d rotation() {
    std::normal_distribution<double> g;
    return Quaterniond(g(gen), g(gen), g(gen), g(gen)).normalized().toRotationMatrix();
  }
  Vector3d box(double half) { return {uniform(-half, half), uniform(-half, half), uniform(-half, half)}; }
  Ellipsoid ellipsoid() {
    return {box(0.05), Vector3d(uniform(0.01, 0.2), uniform(0.01, 0.2), uniform(0.01, 0.2)), rotation()};
  }
};

Vector3d surface_point(const Ellipsoid& e, const Vector3d& u) {
  return e.centre + e.axes * e.semi_axes.cwiseProduct(u.normalized());
}

// The least height n_b . x over the surface near direction u0 (x = c + Q diag(a) u), by golden sections along two
// tangent directions in turn; the height on the unit sphere of u is linear, so its Hessian there is isotropic and a
// few sweeps converge.
Vector3d refined_lowest(const Ellipsoid& e, const Vector3d& n_b, Vector3d u0) {
  for (int sweep = 0; sweep < 6; ++sweep) {
    const Vector3d t1 = u0.unitOrthogonal(), t2 = u0.cross(t1);
    for (const Vector3d& t : {t1, t2}) {
      auto z = [&](double s) { return n_b.dot(surface_point(e, u0 + s * t)); };
      double lo = -0.1, hi = 0.1;
      for (int i = 0; i < 120; ++i) {
        const double m1 = lo + 0.381966 * (hi - lo), m2 = lo + 0.618034 * (hi - lo);
        if (z(m1) < z(m2)) hi = m2; else lo = m1;
      }
      u0 = (u0 + 0.5 * (lo + hi) * t).normalized();
    }
  }
  return surface_point(e, u0);
}

// The orientation R(t) of a body turning at omega0 + alpha t (world axes) from R0, by RK4 on its quaternion
// (dq/dt = (0, omega) q / 2) in `steps` steps; t may be negative.
Matrix3d rotated(const Matrix3d& R0, const Vector3d& omega0, const Vector3d& alpha, double t, int steps = 400) {
  auto rate = [&](double s, const Eigen::Vector4d& q) {  // q as (x, y, z, w), Eigen's coefficient order
    const Vector3d om = omega0 + alpha * s;
    return Eigen::Vector4d(0.5 * (Quaterniond(0.0, om.x(), om.y(), om.z()) * Quaterniond(q)).coeffs());
  };
  Eigen::Vector4d q = Quaterniond(R0).coeffs();
  const double h = t / steps;
  for (int i = 0; i < steps; ++i) {
    const double s = i * h;
    const Eigen::Vector4d k1 = rate(s, q), k2 = rate(s + h / 2, q + h / 2 * k1), k3 = rate(s + h / 2, q + h / 2 * k2),
                          k4 = rate(s + h, q + h * k3);
    q += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return Quaterniond(q).normalized().toRotationMatrix();
}

// 1. Equal semi-axes: the sphere of sections 3, 9 and 13.1.
TEST(EllipsoidTest, EqualSemiAxesIsTheSphere) {
  Draw draw;
  double worst_p = 0.0, worst_jacobian = 0.0, worst_radius = 0.0, worst_bias = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double r = draw.uniform(0.001, 0.1);
    const Ellipsoid e{draw.box(0.05), Vector3d::Constant(r), draw.rotation()};
    const Vector3d n_b = draw.unit();
    // The sphere's contact point is c - r n_b: it moves in the body only with n_b.
    worst_p = std::max(worst_p, (top_sim::ellipsoid_lowest_point(e, n_b) - (e.centre - r * n_b)).norm() / r);
    const Matrix3d sphere_jacobian = -r * (Matrix3d::Identity() - n_b * n_b.transpose());
    worst_jacobian = std::max(
        worst_jacobian, (top_sim::ellipsoid_lowest_point_jacobian(e, n_b) - sphere_jacobian).cwiseAbs().maxCoeff() / r);
    const top_sim::CurvatureRadii radii = top_sim::ellipsoid_curvature_radii(e, n_b);
    worst_radius = std::max({worst_radius, std::abs(radii.r1 - r) / r, std::abs(radii.r2 - r) / r,
                             std::abs(top_sim::hertz_mean_radius(radii) - r) / r});
    // A sphere centred on the figure axis (offset d = -f, body axis e_3) on the plane n = e_z: section 13.1's
    // r_k = d f_hat - r n and r_k' = d f_hat', and section 9's b holds f omega x (omega x f_hat) = -(our bias).
    const double d = draw.uniform(-0.05, 0.05);
    const Ellipsoid tip{d * Vector3d::UnitZ(), Vector3d::Constant(r), draw.rotation()};
    const Matrix3d R = draw.rotation();
    const Vector3d omega = draw.box(50.0), n = Vector3d::UnitZ(), f_hat = R.col(2);
    const top_sim::EllipsoidContact c = top_sim::ellipsoid_contact(tip, R, n, omega);
    top_sim::ContactShape sphere;
    sphere.offset = d;
    sphere.radius = r;
    const top_sim::ShapePoint point = top_sim::shape_point(sphere, f_hat, omega);
    const double scale = omega.squaredNorm() * (std::abs(d) + r), f = -d;
    const Vector3d section9 = f * omega.cross(omega.cross(f_hat));
    // the contact point moves with the sphere's centre (section 3: d r_t/dt = u): r_P' = omega x R c = r_k'
    const Vector3d r_P_rate = omega.cross(c.r_P) + c.surface_rate;
    worst_bias = std::max({worst_bias, (c.r_P - point.r).norm() / (std::abs(d) + r),
                           (r_P_rate - point.r_rate).norm() / (omega.norm() * (std::abs(d) + r)),
                           (c.bias + section9).norm() / scale, (c.bias - omega.cross(point.r_rate)).norm() / scale,
                           std::abs(n.dot(c.bias) + f * n.dot(omega.cross(omega.cross(f_hat)))) / scale});
  }
  EXPECT_LE(worst_p, 1e-15);
  EXPECT_LE(worst_jacobian, 4e-15);  // A = r^2 Q Q^T is the identity's multiple only to a few roundings
  EXPECT_LE(worst_radius, 4e-15);
  EXPECT_LE(worst_bias, 1e-15);
  std::printf("sphere: p %.2e, dp/dn %.2e, radii %.2e, bias %.2e (relative)\n", worst_p, worst_jacobian, worst_radius,
              worst_bias);
}

// 2. The lowest point is lowest, lies on the surface, and the surface's normal there is -n_b.
TEST(EllipsoidTest, LowestPointIsLowestOnSampledSurfaces) {
  Draw draw;
  double worst_below = 0.0, worst_argmin = 0.0, worst_surface = 0.0, worst_normal = 0.0;
  for (int k = 0; k < 40; ++k) {
    const Ellipsoid e = draw.ellipsoid();
    const Vector3d n_b = draw.unit(), p = top_sim::ellipsoid_lowest_point(e, n_b);
    const double h = n_b.dot(p);
    EXPECT_NEAR(top_sim::ellipsoid_support_height(e, n_b), h, 1e-15);
    Vector3d best_u = draw.unit();
    for (int i = 0; i < 20000; ++i) {
      const Vector3d u = draw.unit();
      worst_below = std::max(worst_below, h - n_b.dot(surface_point(e, u)));
      if (n_b.dot(surface_point(e, u)) < n_b.dot(surface_point(e, best_u))) best_u = u;
    }
    worst_argmin = std::max(worst_argmin, std::abs(n_b.dot(refined_lowest(e, n_b, best_u)) - h));
    const Matrix3d A_inv = top_sim::ellipsoid_shape_matrix(e).inverse();
    worst_surface = std::max(worst_surface, std::abs((p - e.centre).dot(A_inv * (p - e.centre)) - 1.0));
    const Vector3d normal = (A_inv * (p - e.centre)).normalized();  // outward, at p
    worst_normal = std::max(worst_normal, (normal + n_b).norm());
  }
  EXPECT_LE(worst_below, 1e-15);  // no sampled point below p but by rounding (heights of 0.3 m at most)
  EXPECT_LE(worst_argmin, 1e-12);
  EXPECT_LE(worst_surface, 1e-13);
  EXPECT_LE(worst_normal, 1e-12);
  std::printf("lowest: sampled below %.2e m, argmin %.2e m, on surface %.2e, normal %.2e\n", worst_below, worst_argmin,
              worst_surface, worst_normal);
}

// 3a. dp/dn_b and dp/dt against central differences.
TEST(EllipsoidTest, JacobianAndRateMatchCentralDifferences) {
  Draw draw;
  const double dn = 1e-5, dt = 1e-5;  // steps: of n_b (dimensionless), of time [s]
  double worst_jacobian = 0.0, worst_rate = 0.0, worst_null = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Ellipsoid e = draw.ellipsoid();
    const Vector3d n_b = draw.unit(), Omega = draw.box(20.0);
    const Matrix3d J = top_sim::ellipsoid_lowest_point_jacobian(e, n_b);
    const double size = e.semi_axes.maxCoeff();
    for (int i = 0; i < 3; ++i) {
      const Vector3d step = dn * Vector3d::Unit(i);
      const Vector3d column = (top_sim::ellipsoid_lowest_point(e, n_b + step) -
                               top_sim::ellipsoid_lowest_point(e, n_b - step)) / (2 * dn);
      // p is homogeneous of degree 0 in n_b, so the unnormalised difference is the Jacobian's column
      worst_jacobian = std::max(worst_jacobian, (column - J.col(i)).norm() / J.norm());
    }
    worst_null = std::max(worst_null, (J * n_b).norm() / size);
    // n_b(t) = exp(-[Omega]x t) n_b for a body turning at a constant Omega
    auto p_at = [&](double t) {
      return top_sim::ellipsoid_lowest_point(e, Eigen::AngleAxisd(-Omega.norm() * t, Omega.normalized()) * n_b);
    };
    const Vector3d rate = top_sim::ellipsoid_lowest_point_rate(e, n_b, Omega);
    worst_rate = std::max(worst_rate, ((p_at(dt) - p_at(-dt)) / (2 * dt) - rate).norm() / (Omega.norm() * J.norm()));
  }
  EXPECT_LE(worst_jacobian, 1e-8);
  EXPECT_LE(worst_rate, 1e-6);
  EXPECT_LE(worst_null, 1e-14);
  std::printf("finite differences: dp/dn %.2e, dp/dt %.2e (relative to |dp/dn|), (dp/dn) n %.2e\n", worst_jacobian,
              worst_rate, worst_null);
}

// 3b. The curvature radii: the support function's second derivative on the tangent plane, the closed forms on the
// axes, and the Gaussian curvature 1 / (a1 a2 a3 sum x_i^2 / a_i^4)^2 at any point.
TEST(EllipsoidTest, CurvatureRadiiMatchSupportFunctionAndClosedForms) {
  Draw draw;
  const double ds = 1e-4;  // step on the tangent plane (dimensionless)
  double worst_numeric = 0.0, worst_axis = 0.0, worst_gauss = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Ellipsoid e = draw.ellipsoid();
    const Vector3d n_b = draw.unit(), t1 = n_b.unitOrthogonal(), t2 = n_b.cross(t1);
    auto h = [&](double s1, double s2) { return top_sim::ellipsoid_support_height(e, n_b + s1 * t1 + s2 * t2); };
    const double h11 = (h(ds, 0) - 2 * h(0, 0) + h(-ds, 0)) / (ds * ds),
                 h22 = (h(0, ds) - 2 * h(0, 0) + h(0, -ds)) / (ds * ds),
                 h12 = (h(ds, ds) - h(ds, -ds) - h(-ds, ds) + h(-ds, -ds)) / (4 * ds * ds);
    const double mean = -0.5 * (h11 + h22), half_gap = std::hypot(0.5 * (h11 - h22), h12);
    const top_sim::CurvatureRadii radii = top_sim::ellipsoid_curvature_radii(e, n_b);
    worst_numeric = std::max({worst_numeric, std::abs(radii.r1 - (mean - half_gap)) / radii.r2,
                              std::abs(radii.r2 - (mean + half_gap)) / radii.r2});
    const Vector3d x = e.axes.transpose() * (top_sim::ellipsoid_lowest_point(e, n_b) - e.centre);  // own axes
    const Vector3d a = e.semi_axes;
    const double sum = x.cwiseAbs2().cwiseQuotient(a.cwiseAbs2().cwiseAbs2()).sum();
    const double gauss_radius = a.prod() * sum;  // sqrt(R1 R2) = 1 / sqrt(K)
    worst_gauss = std::max(worst_gauss, std::abs(top_sim::hertz_mean_radius(radii) - gauss_radius) / gauss_radius);
    // On the axes of an axis-aligned ellipsoid: at the end of axis i the radii are a_j^2 / a_i, a_k^2 / a_i.
    const Ellipsoid aligned{e.centre, a, Matrix3d::Identity()};
    for (int i = 0; i < 3; ++i) {
      const double rj = a((i + 1) % 3) * a((i + 1) % 3) / a(i), rk = a((i + 2) % 3) * a((i + 2) % 3) / a(i);
      for (double sign : {1.0, -1.0}) {
        const top_sim::CurvatureRadii on_axis = top_sim::ellipsoid_curvature_radii(aligned, sign * Vector3d::Unit(i));
        worst_axis = std::max({worst_axis, std::abs(on_axis.r1 - std::min(rj, rk)) / std::max(rj, rk),
                               std::abs(on_axis.r2 - std::max(rj, rk)) / std::max(rj, rk)});
      }
    }
  }
  EXPECT_LE(worst_numeric, 1e-6);
  EXPECT_LE(worst_axis, 1e-15);
  EXPECT_LE(worst_gauss, 1e-13);
  std::printf("curvature: numeric %.2e, on axes %.2e, Gauss %.2e (relative)\n", worst_numeric, worst_axis, worst_gauss);
}

// A body moving with constant a and alpha (world axes) from r0 = 0, v0, R0, omega0: the gap n . (r + R p) of its
// lowest point, and the material velocity of the body at that (moving) point.
struct Motion {
  Ellipsoid e;
  Matrix3d R0;
  Vector3d v0, omega0, a, alpha, n;
  double gap(double t) const {
    const Matrix3d R = rotated(R0, omega0, alpha, t);
    return n.dot(v0 * t + 0.5 * a * t * t) + top_sim::ellipsoid_support_height(e, R.transpose() * n);
  }
  Vector3d contact_velocity(double t) const {
    const Matrix3d R = rotated(R0, omega0, alpha, t);
    return v0 + a * t + (omega0 + alpha * t).cross(R * top_sim::ellipsoid_lowest_point(e, R.transpose() * n));
  }
};

Motion random_motion(Draw& draw) {
  return {draw.ellipsoid(), draw.rotation(), draw.box(1.0), draw.box(10.0), draw.box(10.0), draw.box(100.0),
          draw.unit()};
}

// 4a. The gap's second derivative n . (a + alpha x r_P + omega x (omega x r_P) + omega x R dp/dt) against the
// central second difference of the integrated motion's gap, extrapolated (Richardson, steps T and T/2); without the
// surface term omega x R dp/dt it is wrong.
TEST(EllipsoidTest, GapAccelerationMatchesIntegratedMotion) {
  Draw draw;
  const double T = 5e-4;  // [s]: the extrapolated error falls as T^4 (4.8e-9 here, 7.5e-8 at 1e-3)
  double worst = 0.0, least_without = 1e300;
  for (int k = 0; k < 40; ++k) {
    const Motion m = random_motion(draw);
    auto second = [&](double t) { return (m.gap(t) - 2 * m.gap(0.0) + m.gap(-t)) / (t * t); };
    const double measured = (4 * second(T / 2) - second(T)) / 3;
    const top_sim::EllipsoidContact c = top_sim::ellipsoid_contact(m.e, m.R0, m.n, m.omega0);
    const double r = c.r_P.norm(), scale = m.a.norm() + m.alpha.norm() * r + m.omega0.squaredNorm() * r;
    const double predicted = top_sim::gap_acceleration(c, m.n, m.a, m.alpha);
    worst = std::max(worst, std::abs(predicted - measured) / scale);
    const double without = m.n.dot(m.a + m.alpha.cross(c.r_P) + m.omega0.cross(m.omega0.cross(c.r_P)));
    least_without = std::min(least_without, std::abs(without - measured) / scale);
    EXPECT_NEAR(top_sim::gap_acceleration(c, m.n, Vector3d::Zero(), Vector3d::Zero()), m.n.dot(c.bias), 1e-15 * scale);
  }
  EXPECT_LE(worst, 1e-7);
  EXPECT_GE(least_without, 1e-4);
  std::printf("gap'': %.2e relative to |a| + |alpha| |r_P| + |omega|^2 |r_P|; without omega x R dp/dt at least %.2e\n",
              worst, least_without);
}

// 4b. Accelerations that satisfy the rolling condition a + alpha x r_P + bias = 0 (alpha drawn, a from it), from a
// contact at rest (v0 = -omega0 x r_P): the contact's material velocity stays O(T^2), the gap O(T^3). Without the
// surface term in the bias the velocity grows as O(T).
TEST(EllipsoidTest, RollingConditionKeepsTheContactAtRest) {
  Draw draw;
  double least_order = 1e300, worst_size = 0.0, greatest_order_without = 0.0, least_gap_order = 1e300;
  for (int k = 0; k < 40; ++k) {
    Motion m = random_motion(draw);
    const top_sim::EllipsoidContact c = top_sim::ellipsoid_contact(m.e, m.R0, m.n, m.omega0);
    m.v0 = -m.omega0.cross(c.r_P);
    m.a = -(m.alpha.cross(c.r_P) + c.bias);
    ASSERT_LE(top_sim::contact_acceleration(c, m.a, m.alpha).norm(), 1e-12 * m.a.norm());
    const double r = c.r_P.norm(), w = m.omega0.norm() + std::sqrt(m.alpha.norm());  // a rate [1/s]
    const double T = 1e-3, v1 = m.contact_velocity(T).norm(), v2 = m.contact_velocity(T / 2).norm();
    least_order = std::min(least_order, std::log2(v1 / v2));
    worst_size = std::max(worst_size, v1 / (w * w * w * r * T * T));  // |v_P(T)| against (w T)^2 w r
    least_gap_order = std::min(least_gap_order, std::log2(std::abs(m.gap(T) - m.gap(0.0)) /
                                                          std::abs(m.gap(T / 2) - m.gap(0.0))));
    Motion without = m;
    without.a = -(m.alpha.cross(c.r_P) + m.omega0.cross(m.omega0.cross(c.r_P)));
    greatest_order_without = std::max(
        greatest_order_without, std::log2(without.contact_velocity(T).norm() / without.contact_velocity(T / 2).norm()));
  }
  EXPECT_GE(least_order, 1.9);
  EXPECT_LE(worst_size, 10.0);
  EXPECT_GE(least_gap_order, 2.9);
  EXPECT_LE(greatest_order_without, 1.1);
  std::printf("rolling: |v_P| order >= %.3f, |v_P(T)| <= %.2f (w T)^2 w r; gap order >= %.3f; without the surface "
              "term order <= %.3f\n", least_order, worst_size, least_gap_order, greatest_order_without);
}

// 5. The solver's split of section 14.1: with Newton-Euler (m a = m g + F, J Omega' + Omega x J Omega = R^T (r_P x F)),
// d/dt v_P = K F + b, K = 1/m - [r_P]x R J^-1 R^T [r_P]x, b = g + r_P x (R J^-1 (Omega x J Omega)) + bias; the
// force from K F = -b rolls (contact_acceleration 0).
TEST(EllipsoidTest, RollingForceFromTheBiasHoldsTheContact) {
  Draw draw;
  const Vector3d g(0.0, 0.0, -9.81);
  double worst_split = 0.0, worst_rolling = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Motion m = random_motion(draw);
    const double mass = draw.uniform(0.01, 1.0);
    const Matrix3d Q = draw.rotation(), J = mass * 1e-3 * Q * draw.box(1.0).cwiseAbs().asDiagonal() * Q.transpose() +
                                              mass * 1e-4 * Matrix3d::Identity();  // any positive definite inertia
    const top_sim::EllipsoidContact c = top_sim::ellipsoid_contact(m.e, m.R0, m.n, m.omega0);
    const Vector3d Omega = m.R0.transpose() * m.omega0;
    auto accelerations = [&](const Vector3d& F) {  // Newton-Euler: (a, alpha) under the contact force F
      const Vector3d Omega_dot = J.inverse() * (m.R0.transpose() * c.r_P.cross(F) - Omega.cross(J * Omega));
      return std::make_pair(Vector3d(g + F / mass), Vector3d(m.R0 * Omega_dot));
    };
    Matrix3d r_x;
    r_x << 0.0, -c.r_P.z(), c.r_P.y(), c.r_P.z(), 0.0, -c.r_P.x(), -c.r_P.y(), c.r_P.x(), 0.0;
    const Matrix3d K = Matrix3d::Identity() / mass - r_x * m.R0 * J.inverse() * m.R0.transpose() * r_x;
    const Vector3d b = g + c.r_P.cross(m.R0 * (J.inverse() * Omega.cross(J * Omega))) + c.bias;
    const Vector3d F = draw.box(mass * 100.0);
    const auto [a, alpha] = accelerations(F);
    const double scale = (K * F).norm() + b.norm();
    worst_split = std::max(worst_split, (top_sim::contact_acceleration(c, a, alpha) - (K * F + b)).norm() / scale);
    const auto [a_roll, alpha_roll] = accelerations(K.ldlt().solve(-b));
    worst_rolling = std::max(worst_rolling, top_sim::contact_acceleration(c, a_roll, alpha_roll).norm() / b.norm());
  }
  EXPECT_LE(worst_split, 1e-12);
  EXPECT_LE(worst_rolling, 1e-10);
  std::printf("solver: d/dt v_P = K F + b to %.2e, rolling force's contact acceleration %.2e (relative)\n",
              worst_split, worst_rolling);
}

}  // namespace
