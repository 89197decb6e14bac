// The lowest point of a sphere or a rim on the figure axis and its kinematics (physics.md section 13).
#include "top_sim/contact_shapes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace top_sim {

const char* to_string(ShapeKind kind) { return kind == ShapeKind::sphere ? "sphere" : "rim"; }

double shape_height(const ContactShape& shape, double c) {
  if (shape.kind == ShapeKind::sphere) return shape.offset * c - shape.radius;
  return shape.offset * c - shape.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
}

ShapePoint shape_point(const ContactShape& shape, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d f_dot = w.cross(f_hat);
  const double c = f_hat.z(), d = shape.offset;
  ShapePoint p;
  if (shape.kind == ShapeKind::sphere) {
    p.r = d * f_hat - shape.radius * n;
    p.r_rate = d * f_dot;
    p.height = d * c - shape.radius;
    p.height_slope = d;
    return p;
  }
  // The rim's lowest point is rho e below its centre, e = (n - c f_hat) / s the unit vector of n's part normal to
  // f_hat; as f_hat turns, e turns too, so the point runs along the rim.
  const Eigen::Vector3d n_normal = n - c * f_hat;
  const double s = n_normal.norm(), c_dot = f_dot.z(), s_dot = -c * c_dot / s;
  const Eigen::Vector3d e = n_normal / s;
  const Eigen::Vector3d e_dot = (-c_dot * f_hat - c * f_dot) / s - s_dot / s * e;
  p.r = d * f_hat - shape.radius * e;
  p.r_rate = d * f_dot - shape.radius * e_dot;
  p.height = d * c - shape.radius * s;
  p.height_slope = d + shape.radius * c / s;
  return p;
}

std::size_t lowest_shape(const ShapeSet& shapes, const Eigen::Vector3d& f_hat) {
  std::size_t lowest = 0;
  for (std::size_t k = 1; k < shapes.count; ++k)
    if (shape_height(shapes.shape[k], f_hat.z()) < shape_height(shapes.shape[lowest], f_hat.z())) lowest = k;
  return lowest;
}

}  // namespace top_sim
