// Every derived quantity of one instant, computed once in the core; adapters map it field by field.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "top_sim/contact.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/model.hpp"
#include "top_sim/regime.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

struct Snapshot {
  double t = 0.0;                 // simulated time [s], monotonic across resets
  double alpha = 0.0;             // inclination [rad]
  // Plane frame P.
  Eigen::Vector3d tip_center = Eigen::Vector3d::Zero();   // r_m
  Eigen::Vector3d com = Eigen::Vector3d::Zero();          // r_cm
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body axes, z = figure axis
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d tip_velocity = Eigen::Vector3d::Zero(); // u (= contact-point velocity)
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d figure_axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // shell
  double spin = 0.0;              // omega . f_hat
  bool has_rotor = false;
  double rotor_spin = 0.0;        // absolute rotor spin Omega (0 without rotor)
  double spin_phase = 0.0;        // psi
  double slip = 0.0;
  double mu = 0.0;
  double normal_force = 0.0;
  double drilling_torque = 0.0;   // n . M_n [N m] (physics.md section 12; 0 on a point contact)
  double patch_radius = 0.0;      // a [m] (0 on a point contact and in flight)
  Eigen::Vector3d friction_force = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_acceleration = Eigen::Vector3d::Zero();
  double phi = 0.0;               // direction of travel of the contact point, from h towards downhill
  bool has_stationary_state = false;
  double phi_star = 0.0;          // meaningful only with has_stationary_state
  RegimeIndicators indicators;
  Regime regime = Regime::nutating;
  ContactMode contact_mode = ContactMode::slipping;  // physics.md section 9, separate from the regime
  double gap = 0.0;               // height of the touching shape above the plane [m], 0 in contact
  std::uint32_t touching = 0;     // bit i: shape i of top.shapes touches (the tip sphere is shape 0); 0 in flight
  double energy = 0.0;
  double dissipated_work = 0.0;
  double energy_balance_residual = 0.0;
  ContactFault fault = ContactFault::none;
  std::string fault_message;
  EndState end_state = EndState::none;  // a named end that stopped the run, no fault (physics.md section 13)
  std::string end_message;
};

// True when every number of the snapshot is finite. The Simulator keeps its snapshots finite (a numerical fault
// stops at the last finite state); adapters check again before publishing.
bool all_finite(const Snapshot& s);

}  // namespace top_sim
