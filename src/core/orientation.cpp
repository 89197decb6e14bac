// Orientation convention of physics.md section 2.
#include "orientation.hpp"

namespace top_sim {

Eigen::Quaterniond body_orientation(const Eigen::Vector3d& f_hat, double psi) {
  // R_min(n -> f_hat): rotation about n x f_hat by the angle between them.
  const Eigen::Quaterniond tilt = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), f_hat.normalized());
  return (tilt * Eigen::Quaterniond(Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()))).normalized();
}

}  // namespace top_sim
