// Internal, not yet called by the Simulator: the contact geometry of an ellipsoid on a plane, for the general rigid
// body of physics.md section 14 (14.1 derives it): the lowest point, its motion over the surface, the curvature radii
// there and the acceleration-level terms of the gap and of rolling. Pure functions of their arguments, SI units.
#pragma once

#include <Eigen/Core>

namespace top_sim {

// An ellipsoid fixed in the body: the points c + Q diag(a) u, |u| = 1.
struct Ellipsoid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();     // c: from the centre of mass, body axes [m]
  Eigen::Vector3d semi_axes = Eigen::Vector3d::Zero();  // a_1, a_2, a_3 [m], each > 0 (not checked here)
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   // Q: rotation from the ellipsoid's axes to the body's
};

// A = Q diag(a_i^2) Q^T: the surface is (x - c)^T A^-1 (x - c) = 1, and the support along u is sqrt(u^T A u).
Eigen::Matrix3d ellipsoid_shape_matrix(const Ellipsoid& e);

// The lowest point along the plane's unit normal n_b (body axes): p = c - A n_b / sqrt(n_b^T A n_b), body axes.
Eigen::Vector3d ellipsoid_lowest_point(const Ellipsoid& e, const Eigen::Vector3d& n_b);

// The support height h = n_b . p = n_b . c - sqrt(n_b^T A n_b): the gap is n . r_cm + h (plane through the origin).
double ellipsoid_support_height(const Ellipsoid& e, const Eigen::Vector3d& n_b);

// dp/dn_b = -(A / s - A n_b n_b^T A / s^3), s = sqrt(n_b^T A n_b): the Hessian of h, symmetric, (dp/dn_b) n_b = 0.
Eigen::Matrix3d ellipsoid_lowest_point_jacobian(const Ellipsoid& e, const Eigen::Vector3d& n_b);

// dp/dt = -(dp/dn_b) (Omega x n_b): the contact point's velocity over the surface, body axes, for the body's angular
// velocity Omega in body axes (n_b turns at -Omega x n_b).
Eigen::Vector3d ellipsoid_lowest_point_rate(const Ellipsoid& e, const Eigen::Vector3d& n_b,
                                            const Eigen::Vector3d& Omega);

// The principal radii of curvature at the lowest point, r1 <= r2 [m].
struct CurvatureRadii {
  double r1 = 0.0;
  double r2 = 0.0;
};

// The radii are the eigenvalues of -dp/dn_b (minus the support height's Hessian) on the tangent plane.
CurvatureRadii ellipsoid_curvature_radii(const Ellipsoid& e, const Eigen::Vector3d& n_b);

// The Hertz radius of a patch at a contact of two radii (physics.md sections 12 and 14): sqrt(R1 R2).
double hertz_mean_radius(const CurvatureRadii& radii);

// The lowest point's kinematics in world axes, for a body at rotation R (body to world) turning at omega (world).
struct EllipsoidContact {
  Eigen::Vector3d r_P = Eigen::Vector3d::Zero();           // R p: the contact point from the centre of mass
  Eigen::Vector3d surface_rate = Eigen::Vector3d::Zero();  // R dp/dt: its velocity over the body's surface
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();          // omega x (omega x r_P + R dp/dt)
};

// The rolling condition's terms free of a and alpha: omega x (omega x r_P + surface_rate) (section 14.1).
Eigen::Vector3d rolling_bias(const Eigen::Vector3d& omega, const Eigen::Vector3d& r_P,
                             const Eigen::Vector3d& surface_rate);

// The ellipsoid's contact kinematics against the plane of unit normal n (world axes).
EllipsoidContact ellipsoid_contact(const Ellipsoid& e, const Eigen::Matrix3d& R, const Eigen::Vector3d& n,
                                   const Eigen::Vector3d& omega);

// The rate of the body's material velocity at the moving contact point: a + alpha x r_P + bias (0 while rolling).
Eigen::Vector3d contact_acceleration(const EllipsoidContact& contact, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& alpha);

// The gap's second derivative n . (a + alpha x r_P + bias); its bias alone is n . bias.
double gap_acceleration(const EllipsoidContact& contact, const Eigen::Vector3d& n, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& alpha);

}  // namespace top_sim
