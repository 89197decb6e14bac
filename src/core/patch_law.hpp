// The coupled sliding and drilling law of physics.md section 12 per newton of normal force, and the stuck patch's
// force and impulse, for every contact that has a patch (the tip sphere in dynamics.cpp and contact_modes.cpp, each
// shape of a body of shapes in shape_motion.cpp).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "exact_law_table.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/model.hpp"

namespace top_sim {

// The coupled law of section 12 per newton of normal force at lever Rbar: F / N = -force_per_speed v_t and
// M_n / N = drilling, with s the generalised slip. Inline: a Hertz patch evaluates it twice per right-hand side.
struct PatchLaw {
  double slip, mu, force_per_speed, drilling, force_factor_per_speed;
};
[[gnu::always_inline]] inline PatchLaw patch_law(const Model& model, double lever, double slip_speed, double omega_n,
                                                 double speed_sum) {
  const double v_eps = model.regularization_speed;
  const double wy = lever * omega_n, pivot = std::abs(wy), w2 = slip_speed * slip_speed + wy * wy;
  // A finite lever * omega_n beyond 1e154 (a patch radius of 1e180 m) squares to inf: then |w| by hypot.
  const bool square = std::isfinite(w2);
  const double w = square ? std::sqrt(w2) : std::hypot(slip_speed, wy);
  const double inverse_w = square ? 1.0 / std::sqrt(w2 + v_eps * v_eps) : 1.0 / std::hypot(w, v_eps);
  PatchLaw law;
  law.slip = w / (speed_sum + pivot);
  law.mu = friction_coefficient(model.friction, law.slip);
  const FiniteContact& fc = model.finite_contact;
  const DrillingFactors k = fc.law == DrillingLaw::exact
                                ? exact_law::factors(exact_law::table(fc.pressure), slip_speed, pivot)
                                : DrillingFactors{};
  law.force_factor_per_speed = k.force * inverse_w;
  law.force_per_speed = law.mu * law.force_factor_per_speed;
  law.drilling = square ? -law.mu * lever * k.torque * wy * inverse_w : -law.mu * lever * k.torque * (wy * inverse_w);
  return law;
}

// The stuck patch: its force F and torque M_n about n keep d/dt v_c = 0 and d/dt omega_n = 0:
// [K, -rho x I^-1 n; n . I^-1 (rho x .), n . I^-1 n] (F, M_n) = (b, n . I^-1 G), K the contact's response with the
// rolling resistance's F_z column, n_Ii_tau = n . I^-1 tau_r its part in the last row (rho: the contact point from
// the centre of mass, Ii_n = I^-1 n).
inline Eigen::Vector4d stuck_patch_force(const Eigen::Matrix3d& K, const Eigen::Vector3d& rho, const Eigen::Vector3d& Ii_n,
                                         double n_Ii_tau, const Eigen::Vector3d& b, double n_Ii_G) {
  Eigen::Matrix4d A;
  A.topLeftCorner<3, 3>() = K;
  A.topRightCorner<3, 1>() = -rho.cross(Ii_n);
  for (int j = 0; j < 3; ++j) A(3, j) = Ii_n.dot(rho.cross(Eigen::Vector3d::Unit(j)));
  A(3, 2) += n_Ii_tau;
  A(3, 3) = Eigen::Vector3d::UnitZ().dot(Ii_n);
  Eigen::Vector4d rhs;
  rhs << b, n_Ii_G;
  return A.partialPivLu().solve(rhs);
}

// Section 9's stick impulse on a patch: impulse P and torsional impulse Q with d v_t = -v_t and d omega_n = -omega_n,
// n . v_c unchanged, through the same response without rolling resistance (it has no impulse); K symmetric.
inline Eigen::Vector4d stuck_patch_impulse(const Eigen::Matrix3d& K, const Eigen::Vector3d& rho, const Eigen::Vector3d& Ii_n,
                                           const Eigen::Vector3d& v_c, double omega_n) {
  const Eigen::Vector3d c = -rho.cross(Ii_n);
  Eigen::Matrix4d A;
  A.topLeftCorner<3, 3>() = K;
  A.topRightCorner<3, 1>() = c;
  A.bottomLeftCorner<1, 3>() = c.transpose();
  A(3, 3) = Eigen::Vector3d::UnitZ().dot(Ii_n);
  return A.llt().solve(-Eigen::Vector4d(v_c.x(), v_c.y(), 0.0, omega_n));
}

}  // namespace top_sim
