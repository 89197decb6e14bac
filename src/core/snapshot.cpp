// The one finiteness test of a Snapshot: adapters publish nothing that fails it.
#include "top_sim/snapshot.hpp"

#include <cmath>

namespace top_sim {

bool all_finite(const Snapshot& s) {
  const double scalars[] = {s.t,   s.alpha,        s.spin,      s.rotor_spin, s.spin_phase, s.slip,   s.mu,
                            s.normal_force, s.phi, s.phi_star,  s.gap,        s.energy,     s.dissipated_work,
                            s.energy_balance_residual, s.drilling_torque, s.patch_radius};
  for (double v : scalars)
    if (!std::isfinite(v)) return false;
  const Eigen::Vector3d* vectors[] = {&s.tip_center,   &s.com,         &s.com_velocity,     &s.tip_velocity,
                                      &s.contact_point, &s.figure_axis, &s.angular_velocity, &s.friction_force,
                                      &s.com_acceleration};
  for (const Eigen::Vector3d* v : vectors)
    if (!v->allFinite()) return false;
  return s.orientation.coeffs().allFinite();
}

}  // namespace top_sim
