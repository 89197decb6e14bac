// Finiteness of every snapshot field: shared by the GoogleTest suite and the fuzz targets (no GoogleTest here).
#pragma once

#include <cmath>
#include <string>

#include "top_sim/snapshot.hpp"

namespace top_sim_test {

inline bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// Names of the snapshot fields that are not finite; empty when all are.
inline std::string nonfinite_fields(const top_sim::Snapshot& s) {
  std::string bad;
  auto check = [&bad](bool ok, const char* name) {
    if (!ok) bad += std::string(bad.empty() ? "" : ", ") + name;
  };
  check(std::isfinite(s.t), "t");
  check(std::isfinite(s.alpha), "alpha");
  check(finite(s.tip_center), "tip_center");
  check(finite(s.com), "com");
  check(s.orientation.coeffs().allFinite(), "orientation");
  check(finite(s.com_velocity), "com_velocity");
  check(finite(s.tip_velocity), "tip_velocity");
  check(finite(s.contact_point), "contact_point");
  check(finite(s.figure_axis), "figure_axis");
  check(finite(s.angular_velocity), "angular_velocity");
  check(std::isfinite(s.spin), "spin");
  check(std::isfinite(s.rotor_spin), "rotor_spin");
  check(std::isfinite(s.spin_phase), "spin_phase");
  check(std::isfinite(s.slip), "slip");
  check(std::isfinite(s.mu), "mu");
  check(std::isfinite(s.normal_force), "normal_force");
  check(finite(s.friction_force), "friction_force");
  check(finite(s.com_acceleration), "com_acceleration");
  check(std::isfinite(s.phi), "phi");
  check(std::isfinite(s.phi_star), "phi_star");
  check(std::isfinite(s.indicators.nutation_angle), "indicators.nutation_angle");
  check(std::isfinite(s.indicators.nutation_rate), "indicators.nutation_rate");
  check(std::isfinite(s.indicators.acceleration), "indicators.acceleration");
  check(std::isfinite(s.indicators.speed), "indicators.speed");
  check(std::isfinite(s.energy), "energy");
  check(std::isfinite(s.dissipated_work), "dissipated_work");
  check(std::isfinite(s.energy_balance_residual), "energy_balance_residual");
  return bad;
}

}  // namespace top_sim_test
