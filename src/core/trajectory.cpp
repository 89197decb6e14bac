// The trajectory column table: name, unit and value of each sampled quantity.
#include "top_sim/trajectory.hpp"

#include <cmath>

namespace top_sim {

const std::vector<TrajectoryColumn>& trajectory_columns() {
  using S = const Snapshot&;
  static const std::vector<TrajectoryColumn> columns = {
      {"t", "s", [](S s) { return s.t; }, nullptr},
      {"alpha", "rad", [](S s) { return s.alpha; }, nullptr},
      {"com_x", "m", [](S s) { return s.com.x(); }, nullptr},
      {"com_y", "m", [](S s) { return s.com.y(); }, nullptr},
      {"com_z", "m", [](S s) { return s.com.z(); }, nullptr},
      {"vcm_x", "m/s", [](S s) { return s.com_velocity.x(); }, nullptr},
      {"vcm_y", "m/s", [](S s) { return s.com_velocity.y(); }, nullptr},
      {"vcm_z", "m/s", [](S s) { return s.com_velocity.z(); }, nullptr},
      {"u_x", "m/s", [](S s) { return s.tip_velocity.x(); }, nullptr},
      {"u_y", "m/s", [](S s) { return s.tip_velocity.y(); }, nullptr},
      {"contact_x", "m", [](S s) { return s.contact_point.x(); }, nullptr},
      {"contact_y", "m", [](S s) { return s.contact_point.y(); }, nullptr},
      {"f_x", "1", [](S s) { return s.figure_axis.x(); }, nullptr},
      {"f_y", "1", [](S s) { return s.figure_axis.y(); }, nullptr},
      {"f_z", "1", [](S s) { return s.figure_axis.z(); }, nullptr},
      {"omega_x", "rad/s", [](S s) { return s.angular_velocity.x(); }, nullptr},
      {"omega_y", "rad/s", [](S s) { return s.angular_velocity.y(); }, nullptr},
      {"omega_z", "rad/s", [](S s) { return s.angular_velocity.z(); }, nullptr},
      {"spin", "rad/s", [](S s) { return s.spin; }, nullptr},
      {"rotor_spin", "rad/s", [](S s) { return s.rotor_spin; }, nullptr},
      {"s", "1", [](S s) { return s.slip; }, nullptr},
      {"mu", "1", [](S s) { return s.mu; }, nullptr},
      {"N", "N", [](S s) { return s.normal_force; }, nullptr},
      {"phi", "rad", [](S s) { return s.phi; }, nullptr},
      {"regime", "code", [](S s) { return static_cast<double>(code(s.regime)); },
       [](S s) { return to_string(s.regime); }},
      {"contact_mode", "code", [](S s) { return static_cast<double>(code(s.contact_mode)); },
       [](S s) { return to_string(s.contact_mode); }},
      {"gap", "m", [](S s) { return s.gap; }, nullptr},
      {"energy", "J", [](S s) { return s.energy; }, nullptr},
      {"energy_residual", "J", [](S s) { return s.energy_balance_residual; }, nullptr},
      // Appended last so that the columns before keep their positions in existing readers.
      {"drilling_torque", "N m", [](S s) { return s.drilling_torque; }, nullptr},
      {"patch_radius", "m", [](S s) { return s.patch_radius; }, nullptr},
      // Bit i: shape i of top.shapes touches (physics.md section 13); exact as a double up to bit 31.
      {"touching", "bits", [](S s) { return static_cast<double>(s.touching); }, nullptr},
  };
  return columns;
}

long last_sample_index(double duration, double rate) {
  return static_cast<long>(std::floor(duration * rate * (1.0 + 1e-12)));
}

}  // namespace top_sim
