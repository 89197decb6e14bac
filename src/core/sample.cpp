// The sample: what a reader sees of the committed state, analysed once on the first read (physics.md section 10).
#include "sample.hpp"

#include <cmath>

#include "counters.hpp"
#include "top_sim/adiabatic.hpp"
#include "orientation.hpp"
#include "top_sim/pose.hpp"
#include "shape_motion.hpp"

namespace top_sim {

namespace {

// A regime point's analysis from the dynamics and the energy evaluated already; a sample adds the stationary state
// at its spin.
SampleAnalysis analysis_of(const Model& model, ContactMode mode, const StateVector& y, const Dynamics& dynamics,
                           double energy, const StationaryState& model_stationary) {
  SampleAnalysis a;
  a.dynamics = dynamics;
  if (model.kind != ModelKind::adiabatic)
    a.indicators = regime_indicators(model, mode, y, a.dynamics, model_stationary);
  a.energy = energy;
  return a;
}

}  // namespace

SampleAnalysis regime_point_analysis(const Model& model, ContactMode mode, const StateVector& y,
                                     const StationaryState& model_stationary) {
  Dynamics dynamics;
  evaluate_dynamics(model, mode, y, dynamics);
  return analysis_of(model, mode, y, dynamics, mechanical_energy(model, y), model_stationary);
}


const char* overflowed_part(const SampleAnalysis& a) {
  if (!std::isfinite(a.energy)) return "the energy";
  const Dynamics& d = a.dynamics;
  if (!(std::isfinite(d.mu) && std::isfinite(d.normal_force) && std::isfinite(d.nu_dot) &&
        std::isfinite(d.contact.slip) && d.contact_force.allFinite() && d.omega_dot.allFinite() && d.a_cm.allFinite()))
    return "the dynamics";
  const RegimeIndicators& i = a.indicators;
  if (!(std::isfinite(i.nutation_angle) && std::isfinite(i.nutation_rate) && std::isfinite(i.acceleration) &&
        std::isfinite(i.speed)))
    return "the regime indicators";
  return nullptr;
}

SampleAnalysis analyse_sample(const Model& model, ContactMode mode, const StateVector& y,
                              const StationaryGeometry& geometry) {
  Dynamics dynamics;  // the reduced model's snapshot reads the sleeping state, never the dynamics (make_snapshot)
  if (model.kind == ModelKind::full) evaluate_dynamics(model, mode, y, dynamics);
  return analyse_sample(model, mode, y, geometry, dynamics, mechanical_energy(model, y));
}

SampleAnalysis analyse_sample(const Model& model, ContactMode mode, const StateVector& y,
                              const StationaryGeometry& geometry, const Dynamics& dynamics, double energy) {
  count(work_counters().sample_analyses);
  SampleAnalysis a = analysis_of(model, mode, y, dynamics, energy, geometry.state);
  a.stationary = stationary_state(model, geometry, shell_spin(y));  // and the sleeping state at this spin
  return a;
}

namespace {

// The reduced model's contact: it slides at s* with N = m g cos(alpha) by construction; on a patch
// mu(s*) k_F v_d / |w| = tan(alpha), so mu is the law's (physics.md section 12.1), and a top spinning down slows its
// drift with the spin (w || f_hat, so a_cm = u').
void reduced_contact(const Model& model, const StationaryGeometry& geometry, const StateVector& y,
                     const StationaryState& stationary, Snapshot& s) {
  const Top& top = model.top;
  s.slip = stationary.slip;
  s.mu = stationary.patch_radius > 0.0 ? stationary.mu : std::tan(std::abs(model.plane.inclination));
  s.drilling_torque = stationary.drilling_torque;
  s.patch_radius = stationary.patch_radius;
  s.normal_force = top.mass * model.plane.gravity * std::cos(model.plane.inclination);
  s.friction_force = -top.mass * Eigen::Vector3d(model.plane.g_plane.x(), model.plane.g_plane.y(), 0.0);
  s.com_acceleration.setZero();
  if (point_contact(model)) return;
  StateVector dydt;
  adiabatic_derivative(model, geometry, y, dydt);
  s.com_acceleration = Eigen::Vector3d(dydt[idx::u], dydt[idx::u + 1], 0.0);
  s.friction_force += top.mass * s.com_acceleration;
}

}  // namespace

Snapshot make_snapshot(const Model& model, const StationaryGeometry& geometry, const StateVector& y, double t,
                       const EnergyBalance& balance, const SampleAnalysis& analysis, Regime regime, ContactMode mode) {
  Snapshot s;
  const Dynamics& dyn = analysis.dynamics;
  const StationaryState& stationary = analysis.stationary;
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d u = velocity3(y);
  const TopPose pose = top_pose(model, y, t);  // the fields tf reads without a sample: one definition
  s.t = pose.t;
  s.alpha = pose.alpha;
  s.contact_mode = mode;
  s.gap = y[idx::gap];
  s.touching = touching_shapes(model, mode);
  s.tip_center = pose.tip_center;
  s.com = pose.com;
  s.orientation = pose.orientation;
  s.tip_velocity = u;
  s.com_velocity = u + w.cross(top.com_offset * f_hat);
  if (has_shapes(model)) {  // the state's gap rate is the touching shape's (shape_motion.hpp)
    s.com_velocity = shape_body_com_velocity(model, y);
    s.tip_velocity = s.com_velocity - w.cross(top.com_offset * f_hat);
  }
  s.contact_point = pose.contact_point;
  s.figure_axis = f_hat;
  s.angular_velocity = w;
  s.spin = w.dot(f_hat);
  s.has_rotor = top.has_rotor;
  s.rotor_spin = top.has_rotor ? s.spin + y[idx::nu] : 0.0;
  s.spin_phase = y[idx::psi];
  if (model.kind == ModelKind::adiabatic) {
    reduced_contact(model, geometry, y, stationary, s);
  } else {
    s.slip = mode == ContactMode::rolling ? 0.0 : dyn.contact.slip;
    s.mu = dyn.mu;
    s.normal_force = dyn.normal_force;
    s.drilling_torque = dyn.drilling_torque;  // 0 on a point contact and in flight (evaluate_dynamics, motion)
    s.patch_radius = dyn.patch_radius;
    s.friction_force = dyn.friction_force;
    s.com_acceleration = dyn.a_cm;
  }
  s.phi = travel_angle(u.x(), u.y());
  s.has_stationary_state = stationary.exists && stationary.phi_defined;
  s.phi_star = s.has_stationary_state ? stationary.phi : 0.0;
  s.indicators = analysis.indicators;
  s.fault = ContactFault::none;
  if (model.kind == ModelKind::full && dyn.margins.painleve <= 0.0) s.fault = ContactFault::painleve;
  s.regime = regime;
  s.energy = analysis.energy;
  s.dissipated_work = y[idx::w_diss];
  s.energy_balance_residual = balance.residual(analysis.energy, y);  // the analysis' energy is y's
  return s;
}

}  // namespace top_sim
