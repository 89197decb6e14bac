// An ellipsoid's contact geometry on a plane (physics.md section 14.1); not yet called by the Simulator.
#include "ellipsoid.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace top_sim {

Eigen::Matrix3d ellipsoid_shape_matrix(const Ellipsoid& e) {
  return e.axes * e.semi_axes.cwiseAbs2().asDiagonal() * e.axes.transpose();
}

Eigen::Vector3d ellipsoid_lowest_point(const Ellipsoid& e, const Eigen::Vector3d& n_b) {
  const Eigen::Vector3d An = ellipsoid_shape_matrix(e) * n_b;
  return e.centre - An / std::sqrt(n_b.dot(An));
}

double ellipsoid_support_height(const Ellipsoid& e, const Eigen::Vector3d& n_b) {
  return n_b.dot(e.centre) - std::sqrt(n_b.dot(ellipsoid_shape_matrix(e) * n_b));
}

Eigen::Matrix3d ellipsoid_lowest_point_jacobian(const Ellipsoid& e, const Eigen::Vector3d& n_b) {
  const Eigen::Matrix3d A = ellipsoid_shape_matrix(e);
  const Eigen::Vector3d An = A * n_b;
  const double s = std::sqrt(n_b.dot(An));
  return -(A / s - An * An.transpose() / (s * s * s));
}

Eigen::Vector3d ellipsoid_lowest_point_rate(const Ellipsoid& e, const Eigen::Vector3d& n_b,
                                            const Eigen::Vector3d& Omega) {
  return -(ellipsoid_lowest_point_jacobian(e, n_b) * Omega.cross(n_b));
}

CurvatureRadii ellipsoid_curvature_radii(const Ellipsoid& e, const Eigen::Vector3d& n_b) {
  // -dp/dn_b is the inverse of the shape operator on the tangent plane: its eigenvalues there are the radii.
  const Eigen::Matrix3d M = -ellipsoid_lowest_point_jacobian(e, n_b);
  const Eigen::Vector3d t1 = n_b.unitOrthogonal(), t2 = n_b.cross(t1).normalized();
  const double s11 = t1.dot(M * t1), s22 = t2.dot(M * t2), s12 = t1.dot(M * t2);
  const double mean = 0.5 * (s11 + s22), half_gap = std::hypot(0.5 * (s11 - s22), s12);
  return {mean - half_gap, mean + half_gap};
}

double hertz_mean_radius(const CurvatureRadii& radii) { return std::sqrt(radii.r1 * radii.r2); }

Eigen::Vector3d rolling_bias(const Eigen::Vector3d& omega, const Eigen::Vector3d& r_P,
                             const Eigen::Vector3d& surface_rate) {
  return omega.cross(omega.cross(r_P) + surface_rate);
}

EllipsoidContact ellipsoid_contact(const Ellipsoid& e, const Eigen::Matrix3d& R, const Eigen::Vector3d& n,
                                   const Eigen::Vector3d& omega) {
  const Eigen::Vector3d n_b = R.transpose() * n, Omega = R.transpose() * omega;
  EllipsoidContact c;
  c.r_P = R * ellipsoid_lowest_point(e, n_b);
  c.surface_rate = R * ellipsoid_lowest_point_rate(e, n_b, Omega);
  c.bias = rolling_bias(omega, c.r_P, c.surface_rate);
  return c;
}

Eigen::Vector3d contact_acceleration(const EllipsoidContact& contact, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& alpha) {
  return a + alpha.cross(contact.r_P) + contact.bias;
}

double gap_acceleration(const EllipsoidContact& contact, const Eigen::Vector3d& n, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& alpha) {
  return n.dot(contact_acceleration(contact, a, alpha));
}

}  // namespace top_sim
