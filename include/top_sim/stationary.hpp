// The stationary ("sleeping") state and its analytic results (physics.md section 5).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// A root of mu(s) = tan(alpha) on [0, 1]; stable where d mu / d s > 0.
struct SlipRoot {
  double s = 0.0;
  bool stable = false;
};

// All roots of mu(s) = tan_alpha on [0, 1], in increasing s.
std::vector<SlipRoot> slip_roots(const FrictionLaw& law, double tan_alpha);

// Critical inclination alpha_c = atan(max mu): above it no stationary state exists.
double critical_inclination(const FrictionLaw& law);

struct StationaryState {
  bool exists = false;
  std::string reason;          // why not, when !exists (or why phi* is undefined)
  bool phi_defined = false;    // false when the sleeping top does not move (R = 0, alpha = 0, spin = 0)
  double slip = 0.0;           // s* (stable branch)
  double slip_unstable = -1.0; // the unstable root, < 0 when none
  double phi = 0.0;            // phi*: from h towards downhill [rad]
  double rolling_speed = 0.0;  // v_h
  double sliding_speed = 0.0;  // v_d
  Eigen::Vector3d f_hat = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // u* of the tip-sphere centre
  // On a patch (physics.md section 12.1): the law's mu(s*), the patch radius at N = m g cos(alpha) and the drilling
  // torque M_n there (degree 0 in the spin: the same at every spin of one sign); all 0 on a point contact.
  double mu = 0.0;
  double patch_radius = 0.0;
  double drilling_torque = 0.0;
  double friction_force = 0.0;  // |F_t| [N]: m g sin(alpha) less the spin-down's deceleration
  double spin_rate = 0.0;       // d spin / dt from the patch [rad/s^2] (air and bearing not included)
};

// Stable sleeping state for the model's alpha and friction, at shell spin omega* (signed).
StationaryState stationary_state(const Model& model, double spin);

// What no spin changes of the sleeping state (f_hat*, s*, the unstable root, or why none exists), solved once per
// model: a sample at a new spin then pays only omega* and u*, with the same bits as stationary_state(model, spin).
struct StationaryGeometry {
  StationaryState state;                                // omega*, u*, phi* still zero
  double sliding_ratio = 0.0;                           // v_d / v_h = tan(phi+), tan(phi+ / 2) = s*
  Eigen::Vector2d downhill = Eigen::Vector2d::Zero();  // unit vector in the plane; zero on a level plane
  // A patch's drilling torque tilts f_hat* sideways by a sign of the spin's own: one state per sign
  // ([0] spin >= 0, [1] spin < 0), each with its sliding_ratio v_d / v_h; unused on a point contact.
  bool patch = false;
  StationaryState side[2];
  double side_ratio[2] = {0.0, 0.0};
  Eigen::Vector2d side_downhill[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
};
StationaryGeometry stationary_geometry(const Model& model);
StationaryState stationary_state(const Model& model, const StationaryGeometry& geometry, double spin);

// The sleeping state at another root `slip` of mu(s) = tan(alpha) (e.g. slip_unstable, or any s with the plane
// at alpha = atan(mu(s))): the same f_hat* and omega*, the sliding speed and phi* of that slip. The caller
// chooses a root: the friction balance is not checked (slip_unstable stays -1).
StationaryState stationary_state_on_root(const Model& model, double spin, double slip);

// The exact sleeping state vector at `position`; rotor relative spin set from the absolute spin.
StateVector stationary_state_vector(const Model& model, const StationaryState& st, double spin,
                                    const Eigen::Vector2d& position, double rotor_spin);

}  // namespace top_sim
