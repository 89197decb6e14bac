// Orientation convention of physics.md section 2: body frame = R_min(n -> f_hat) * Rot_z(psi).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace top_sim {

// psi' that keeps R_min(n -> f_hat) Rot_z(psi) the body's orientation (singular only at f_z = -1).
inline double spin_phase_rate(const Eigen::Vector3d& f_hat, const Eigen::Vector3d& omega) {
  const double w_f = omega.dot(f_hat);
  return w_f + (omega.z() - w_f * f_hat.z()) / (1.0 + f_hat.z());
}

// Body orientation in the plane frame from the figure axis and the spin phase.
Eigen::Quaterniond body_orientation(const Eigen::Vector3d& f_hat, double psi);

}  // namespace top_sim
