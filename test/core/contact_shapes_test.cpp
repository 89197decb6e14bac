// Contact shapes (physics.md section 13): the lowest point of a sphere and of a rim, its kinematics, and one shape's
// motion: the tip sphere's against dynamics.cpp, a rolling disc's steady motion against Omega^2 a sin(beta) = 4 g.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "test_util.hpp"
#include "top_sim/contact_shapes.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/shape_motion.hpp"

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
