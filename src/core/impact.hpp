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

// A second shape j reaching the plane while the touching shape k stays on it (physics.md 13.3): first the impact at
// j alone (section 9's, j made the touching shape); if it leaves k separating at v_settle or faster it stands, and k
// lets go; else both take a plastic sliding impulse P_i = lambda_i (n - mu_i t_hat_i-), lambda solved from
// n . v_j+ = n . v_k+ = 0 (an impulse at j that would press k into the plane is shared; k, which j's impulse would
// leave slower than v_settle, is held, its impulse pulling by at most that: section 9's settle rule at two shapes). Sets model.shapes (touching, second)
// to what touches after it; W_diss is booked by the caller.
struct SecondTouchdown {
  bool both = false;         // j and k in contact after it (else j alone, or flight when j bounced)
  bool bounced = false;      // j bounced off (Newton's restitution, not plastic): flight
  bool painleve = false;     // no admissible impulse (a denominator or the shared impulse's lambda)
  bool frictionless = false; // the shared sliding impulse would have raised E: taken along n alone
  bool both_tried = false;   // the painleve came from the shared impulse (else from the impact at j alone)
  double denominator = 0.0;  // the failing denominator, or the negative lambda (for the fault message)
};
SecondTouchdown apply_second_touchdown(Model& model, StateVector& y, std::size_t j);

}  // namespace top_sim
