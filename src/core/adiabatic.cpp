// The reduced ("adiabatic") model (physics.md section 7).
#include "top_sim/adiabatic.hpp"

#include <cmath>

#include "orientation.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

std::string adiabatic_validity(const Model& model) {
  const StationaryState st = stationary_state(model, 1.0);
  if (!st.exists) return "model.kind = adiabatic is invalid here: " + st.reason;
  return "";
}

namespace {

// dy/dt on the sleeping manifold: p' = |spin| u_1, u' = sign u_1 spin', omega' = spin' f_hat*, and the given nu',
// W_diss' (u_1: u* at unit spin of the spin's sign).
void sleeping_derivative(const StationaryState& unit, double spin, double spin_dot, double nu_dot, double dissipation,
                         StateVector& dydt) {
  const double sign = spin >= 0.0 ? 1.0 : -1.0;
  const Eigen::Vector2d velocity = std::abs(spin) * unit.velocity, du = sign * unit.velocity * spin_dot;
  dydt.fill(0.0);
  dydt[idx::x] = velocity.x();
  dydt[idx::x + 1] = velocity.y();
  dydt[idx::u] = du.x();
  dydt[idx::u + 1] = du.y();
  for (int i = 0; i < 3; ++i) dydt[idx::omega + i] = spin_dot * unit.f_hat[i];
  dydt[idx::nu] = nu_dot;
  dydt[idx::w_diss] = dissipation;
  dydt[idx::psi] = spin_phase_rate(unit.f_hat, spin * unit.f_hat);
}

// On a patch or with air spin drag the sleeping top spins down: the patch's rate (stationary.cpp, degree 0 in the
// spin), the air's -k spin and the bearing's c nu over I_f' + m |u_1|^2 (the translational energy of u* rides on the
// spin; u_1 = u* at unit spin). W_diss books the sliding |F_t| v_d, the drilling -M_n omega_n, k spin^2, c nu^2.
void spinning_down(const Model& model, const StateVector& y, const StationaryState& unit, double spin,
                   StateVector& dydt) {
  const Top& top = model.top;
  const double inertia = shell_axial_inertia(top) + top.mass * unit.velocity.squaredNorm();
  double torque = -model.air.spin_drag * spin, nu_dot = 0.0, bearing = 0.0;
  if (top.has_rotor) {
    const double c = top.rotor.coupling, nu = y[idx::nu];
    torque += c * nu;
    bearing = c * nu * nu;
  }
  const double spin_dot = unit.spin_rate + torque / inertia;
  if (top.has_rotor) nu_dot = -top.rotor.coupling * y[idx::nu] / top.rotor.inertia_axial - spin_dot;
  const double friction = unit.patch_radius > 0.0 ? unit.friction_force
                         : top.mass * std::abs(std::sin(model.plane.inclination)) * model.plane.gravity;
  const double drilling = -unit.drilling_torque * unit.f_hat.z() * spin;  // -M_n omega_n >= 0
  sleeping_derivative(unit, spin, spin_dot, nu_dot,
                      std::abs(spin) * friction * unit.sliding_speed + drilling + model.air.spin_drag * spin * spin +
                          bearing,
                      dydt);
}

}  // namespace

void adiabatic_derivative(const Model& model, const StationaryGeometry& geometry, const StateVector& y,
                          StateVector& dydt) {
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const double spin = angular_velocity(y).dot(f_hat);
  // u* is linear in the spin for each sign: one solve at unit spin gives u* and du*/d(spin).
  const double sign = spin >= 0.0 ? 1.0 : -1.0;
  const StationaryState unit = stationary_state(model, geometry, sign);
  if (!point_contact(model)) return spinning_down(model, y, unit, spin, dydt);

  // Only the bearing changes the shell spin once asleep: I_f' spin' = c nu, J Omega' = -c nu.
  double spin_dot = 0.0, nu_dot = 0.0, bearing = 0.0;
  if (top.has_rotor) {
    const double c = top.rotor.coupling, nu = y[idx::nu];
    spin_dot = c * nu / shell_axial_inertia(top);
    nu_dot = -c * nu / top.rotor.inertia_axial - spin_dot;
    bearing = c * nu * nu;
  }
  // Friction power mu N |v_t| = tan(alpha) m g cos(alpha) v_d in the sleeping state.
  sleeping_derivative(unit, spin, spin_dot, nu_dot,
                      std::abs(std::sin(model.plane.inclination)) * top.mass * model.plane.gravity * std::abs(spin) *
                              unit.sliding_speed + bearing,
                      dydt);
}

void adiabatic_derivative(const Model& model, const StateVector& y, StateVector& dydt) {
  adiabatic_derivative(model, stationary_geometry(model), y, dydt);
}

void project_to_stationary(const Model& model, const StationaryGeometry& geometry, StateVector& y) {
  const double spin = shell_spin(y);
  const StationaryState st = stationary_state(model, geometry, spin);
  if (!st.exists) return;
  set_velocity(y, st.velocity);
  set_figure_axis(y, st.f_hat);
  set_angular_velocity(y, st.omega);
}

void project_to_stationary(const Model& model, StateVector& y) {
  project_to_stationary(model, stationary_geometry(model), y);
}

}  // namespace top_sim
