// Right-hand side of the full model (physics.md sections 3, 4 and 6).
#include "top_sim/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "top_sim/adiabatic.hpp"
#include "top_sim/orientation.hpp"

namespace top_sim {

namespace {

// I'^-1 v for the axisymmetric inertia about f_hat: closed form, no 3x3 solve.
inline Eigen::Vector3d inverse_inertia_times(double inv_d, double inv_f, const Eigen::Vector3d& f_hat,
                                             const Eigen::Vector3d& v) {
  return inv_d * v + (inv_f - inv_d) * f_hat.dot(v) * f_hat;
}

// Everything but the tilt margin: the right-hand side needs no margins, and cos(theta_max) was 7.5 % of all
// instructions there (callgrind).
void evaluate_motion(const Model& model, const StateVector& y, Dynamics& out) {
  const Top& top = model.top;
  const double m = top.mass;
  const double R = top.tip_radius;
  const double f = top.com_offset;
  const double J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double c = top.has_rotor ? top.rotor.coupling : 0.0;
  const double nu = top.has_rotor ? y[idx::nu] : 0.0;
  const Eigen::Vector3d& g = model.plane.g_plane;

  const Eigen::Vector3d f_hat = figure_axis(y).normalized();  // the state's |f_hat| drifts between renormalisations
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d u = velocity3(y);

  // Section 3: slip and friction direction; section 4: contact force direction d = n - mu t_hat.
  out.contact = contact_kinematics(model, u, w);
  out.mu = friction_coefficient(model.friction, out.contact.slip);
  const Eigen::Vector3d d(-out.mu * out.contact.t_hat.x(), -out.mu * out.contact.t_hat.y(), 1.0);
  const Eigen::Vector3d rho(-f * f_hat.x(), -f * f_hat.y(), -R - f * f_hat.z());  // r_t - r_cm

  // Section 6: L_total = I' omega + J Omega f_hat; shell torque-free part G = omega x L_total - c nu f_hat.
  const double I_d = top.inertia_transverse;
  const double I_fs = top.inertia_axial - J;  // I_f'
  const double inv_d = 1.0 / I_d;
  const double inv_f = 1.0 / I_fs;
  const double w_f = w.dot(f_hat);
  const Eigen::Vector3d L = I_d * w + ((I_fs - I_d) * w_f + J * (w_f + nu)) * f_hat;
  const Eigen::Vector3d G = w.cross(L) - c * nu * f_hat;
  const Eigen::Vector3d Ii_rxd = inverse_inertia_times(inv_d, inv_f, f_hat, rho.cross(d));
  const Eigen::Vector3d Ii_G = inverse_inertia_times(inv_d, inv_f, f_hat, G);
  const Eigen::Vector3d w_x_f = w.cross(f_hat);
  const Eigen::Vector3d centripetal = w.cross(w_x_f);

  double N;
  if (model.normal_force == NormalForceModel::constrained) {
    // Section 4: N (1/m - f A) = -n.g + f (C - B), the multiplier keeping n . a_m = 0.
    const double A = Ii_rxd.cross(f_hat).z();
    const double B = Ii_G.cross(f_hat).z();
    const double C = centripetal.z();
    const double denominator = 1.0 / m - f * A;
    out.margins.painleve = m * denominator;
    // Past the Painleve boundary N is meaningless; keep it finite so the fault can be located.
    const double safe = denominator > 1e-6 / m ? denominator : 1e-6 / m;
    N = (-g.z() + f * (C - B)) / safe;
  } else {
    N = -m * g.z();  // static approximation: N = m g cos(alpha)
    out.margins.painleve = 1.0;
  }
  out.normal_force = N;
  out.margins.normal_force = N;

  out.contact_force = N * d;
  out.friction_force = Eigen::Vector3d(N * (d.x()), N * (d.y()), 0.0);
  out.omega_dot = N * Ii_rxd - Ii_G;
  out.a_cm = g + out.contact_force / m;
  out.a_m = out.a_cm - f * (out.omega_dot.cross(f_hat) + centripetal);
  out.a_m.z() = 0.0;  // the contact holds n . a_m = 0 (exactly for constrained, by construction for static)
  out.nu_dot = top.has_rotor ? -c * nu / J - out.omega_dot.dot(f_hat) : 0.0;
  out.dissipation = out.mu * N * out.contact.t_hat.dot(out.contact.v_t) + c * nu * nu;
  out.psi_dot = spin_phase_rate(f_hat, w);
}

}  // namespace

void evaluate_dynamics(const Model& model, const StateVector& y, Dynamics& out) {
  evaluate_motion(model, y, out);
  out.margins.tilt = figure_axis(y).normalized().z() - std::cos(model.top.max_tilt);
}

void derivative(const Model& model, const StateVector& y, StateVector& dydt) {
  Dynamics dyn;
  evaluate_motion(model, y, dyn);
  const Eigen::Vector3d f_dot = angular_velocity(y).cross(figure_axis(y));  // keeps |f_hat| in the exact flow
  dydt[idx::x] = y[idx::u];
  dydt[idx::x + 1] = y[idx::u + 1];
  dydt[idx::u] = dyn.a_m.x();
  dydt[idx::u + 1] = dyn.a_m.y();
  for (int i = 0; i < 3; ++i) {
    dydt[idx::f + i] = f_dot[i];
    dydt[idx::omega + i] = dyn.omega_dot[i];
  }
  dydt[idx::nu] = dyn.nu_dot;
  dydt[idx::w_diss] = dyn.dissipation;
  dydt[idx::psi] = dyn.psi_dot;
}

void jacobian_difference_steps(const Model& model, const StateVector& y, StateVector& max_step) {
  max_step.fill(0.0);
  const ContactKinematics k = contact_kinematics(model, velocity3(y), angular_velocity(y));
  const double width = 1e-4 * std::max(k.v_t.norm(), model.regularization_speed);
  max_step[idx::u] = max_step[idx::u + 1] = width;
  const double R = model.top.tip_radius;
  if (R > 0.0) max_step[idx::omega] = max_step[idx::omega + 1] = width / R;  // v_t = u - R omega x n
}

void model_derivative(const Model& model, const StateVector& y, StateVector& dydt) {
  if (model.kind == ModelKind::adiabatic)
    adiabatic_derivative(model, y, dydt);
  else
    derivative(model, y, dydt);
}

}  // namespace top_sim
