// The reduced ("adiabatic") model (physics.md section 7).
#include "top_sim/adiabatic.hpp"

#include <cmath>

#include "top_sim/orientation.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

std::string adiabatic_validity(const Model& model) {
  const StationaryState st = stationary_state(model, 1.0);
  if (!st.exists) return "model.kind = adiabatic is invalid here: " + st.reason;
  return "";
}

void adiabatic_derivative(const Model& model, const StateVector& y, StateVector& dydt) {
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const double spin = angular_velocity(y).dot(f_hat);
  // u* is linear in the spin for each sign: one solve at unit spin gives u* and du*/d(spin).
  const double sign = spin >= 0.0 ? 1.0 : -1.0;
  const StationaryState unit = stationary_state(model, sign);
  const Eigen::Vector2d velocity = std::abs(spin) * unit.velocity;

  // Only the bearing changes the shell spin once asleep: I_f' spin' = c nu, J Omega' = -c nu.
  double spin_dot = 0.0, nu_dot = 0.0, bearing = 0.0;
  if (top.has_rotor) {
    const double c = top.rotor.coupling, nu = y[idx::nu];
    spin_dot = c * nu / shell_axial_inertia(top);
    nu_dot = -c * nu / top.rotor.inertia_axial - spin_dot;
    bearing = c * nu * nu;
  }
  const Eigen::Vector2d du = sign * unit.velocity * spin_dot;
  dydt.fill(0.0);
  dydt[idx::x] = velocity.x();
  dydt[idx::x + 1] = velocity.y();
  dydt[idx::u] = du.x();
  dydt[idx::u + 1] = du.y();
  for (int i = 0; i < 3; ++i) dydt[idx::omega + i] = spin_dot * unit.f_hat[i];
  dydt[idx::nu] = nu_dot;
  // Friction power mu N |v_t| = tan(alpha) m g cos(alpha) v_d in the sleeping state.
  dydt[idx::w_diss] = std::abs(std::sin(model.plane.inclination)) * top.mass * model.plane.gravity * std::abs(spin) * unit.sliding_speed + bearing;
  dydt[idx::psi] = spin_phase_rate(unit.f_hat, spin * unit.f_hat);
}

void project_to_stationary(const Model& model, StateVector& y) {
  const double spin = shell_spin(y);
  const StationaryState st = stationary_state(model, spin);
  if (!st.exists) return;
  set_velocity(y, st.velocity);
  set_figure_axis(y, st.f_hat);
  set_angular_velocity(y, st.omega);
}

}  // namespace top_sim
