// The touchdown impact of physics.md section 9: Newton's restitution, Coulomb's bound on the tangential
// impulse, the plastic settle rule.
#pragma once

#include <Eigen/Core>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

struct ImpactResult {
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();  // P at the contact point [N s]
  bool sticking = false;     // branch 1 (|P_t| <= mu_i P_n) rather than the sliding branch 2
  bool plastic = false;      // e_N |n . v_c-| < v_settle: computed with e_N = 0, the contact closes
  bool painleve = false;     // the sliding branch's denominator n . K (n - mu_i t_hat-) <= 0: nothing applied
  double denominator = 0.0;  // that denominator (for the fault message)
  double normal_velocity_before = 0.0;  // n . v_c-
  double normal_velocity_after = 0.0;   // n . v_c+
};

// Applies the impact to y (u including the gap rate, omega, nu); W_diss is booked by the caller.
ImpactResult apply_impact(const Model& model, StateVector& y);

}  // namespace top_sim
