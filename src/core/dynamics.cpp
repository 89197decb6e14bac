// Right-hand side of the full model in each contact mode (physics.md sections 3, 4, 6 and 9).
#include "top_sim/dynamics.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "rigid_body.hpp"
#include "top_sim/adiabatic.hpp"
#include "top_sim/orientation.hpp"

namespace top_sim {

namespace {

// Slipping (sections 3-4): F = N d, d = n - mu t_hat, N the multiplier keeping n . a_m = 0. Sets omega_dot too
// (N I'^-1 (rho x d) - I'^-1 G), reusing I'^-1 (rho x d) from the multiplier.
void slipping_force(const Model& model, const detail::RigidBody& b, Dynamics& out, double& painleve) {
  out.mu = friction_coefficient(model.friction, out.contact.slip);
  const Eigen::Vector3d d(-out.mu * out.contact.t_hat.x(), -out.mu * out.contact.t_hat.y(), 1.0);
  const Eigen::Vector3d Ii_rxd = b.inverse_inertia(b.rho.cross(d));
  double N;
  if (model.normal_force == NormalForceModel::constrained) {
    // Section 4: N (1/m - f A) = -n.g + f (C - B); equal to n.b / (n.K d) of section 9.
    const double A = Ii_rxd.cross(b.f_hat).z();
    const double B = b.Ii_G.cross(b.f_hat).z();
    const double denominator = 1.0 / b.m - b.f * A;
    painleve = b.m * denominator;
    // Past the Painleve boundary N is meaningless; keep it finite so the fault can be located.
    const double safe = denominator > 1e-6 / b.m ? denominator : 1e-6 / b.m;
    N = (-b.g.z() + b.f * (b.centripetal.z() - B)) / safe;
  } else {
    N = -b.m * b.g.z();  // static approximation: N = m g cos(alpha)
    painleve = ModeMargins::kNone;
  }
  out.normal_force = N;
  out.contact_force = N * d;
  out.omega_dot = N * Ii_rxd - b.Ii_G;
  out.dissipation = out.mu * N * out.contact.t_hat.dot(out.contact.v_t);
}

// Rolling (section 9): F = K^-1 b keeps v_c constant; no work is done at the contact.
void rolling_contact_force(const detail::RigidBody& b, Dynamics& out) {
  out.contact_force = b.response_matrix().llt().solve(b.response_bias());
  out.normal_force = out.contact_force.z();
  const double Ft = std::hypot(out.contact_force.x(), out.contact_force.y());
  out.mu = out.normal_force > 0.0 ? Ft / out.normal_force : 0.0;
  out.dissipation = 0.0;
}

// One mode's motion; a template so that the hot slipping path compiles without the other modes' code.
template <ContactMode kMode>
void motion(const Model& model, const StateVector& y, Dynamics& out, double& painleve) {
  const detail::RigidBody b(model, y);
  out.contact = contact_kinematics(model, in_plane_velocity(y), b.w);
  painleve = ModeMargins::kNone;
  if constexpr (kMode == ContactMode::slipping) {
    slipping_force(model, b, out, painleve);
  } else {
    if constexpr (kMode == ContactMode::rolling) {
      rolling_contact_force(b, out);
    } else {
      out.mu = 0.0;
      out.normal_force = 0.0;
      out.contact_force.setZero();
      out.dissipation = 0.0;
    }
    out.omega_dot = b.inverse_inertia(b.rho.cross(out.contact_force)) - b.Ii_G;
  }
  out.friction_force = Eigen::Vector3d(out.contact_force.x(), out.contact_force.y(), 0.0);
  b.accelerations(out.contact_force, out.omega_dot, out.a_cm, out.a_m);
  if constexpr (kMode != ContactMode::flight) out.a_m.z() = 0.0;  // the contact holds n . a_m = 0
  out.nu_dot = model.top.has_rotor ? -b.c * b.nu / b.J - out.omega_dot.dot(b.f_hat) : 0.0;
  out.dissipation += b.c * b.nu * b.nu;
  out.psi_dot = spin_phase_rate(b.f_hat, b.w);
}

// cos(max_tilt), recomputed only when the angle changes: event scans evaluate margins many times per step.
double cos_max_tilt(const Model& model) {
  thread_local double angle = 0.0, cosine = 1.0;
  if (model.top.max_tilt != angle) {
    angle = model.top.max_tilt;
    cosine = std::cos(angle);
  }
  return cosine;
}

void evaluate_motion(const Model& model, ContactMode mode, const StateVector& y, Dynamics& out, double& painleve) {
  switch (mode) {
    case ContactMode::slipping: motion<ContactMode::slipping>(model, y, out, painleve); break;
    case ContactMode::rolling: motion<ContactMode::rolling>(model, y, out, painleve); break;
    case ContactMode::flight: motion<ContactMode::flight>(model, y, out, painleve); break;
  }
}

}  // namespace

void evaluate_dynamics(const Model& model, ContactMode mode, const StateVector& y, Dynamics& out) {
  ContactForceRecord record;
  evaluate_motion(model, mode, y, out, record.painleve);
  record.force = out.contact_force;
  if (margins_from_record(model, mode, y, record, cos_max_tilt(model), out.margins)) return;
  // A slipping contact that may stick: the stick function needs the rolling force at this state.
  const Eigen::Vector3d F = rolling_force(contact_response(model, y));
  const double consistency =
      (std::hypot(F.x(), F.y()) - static_friction(model) * F.z()) / (model.top.mass * model.plane.gravity);
  out.margins.transfer = std::max(out.contact.v_t.norm() / model.contact.stick_speed - 1.0, consistency);
}

void derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                ContactForceRecord* record) {
  Dynamics dyn;
  double painleve;
  evaluate_motion(model, mode, y, dyn, painleve);
  if (record) {
    record->force = dyn.contact_force;
    record->painleve = painleve;
  }
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
  // In contact the gap and its rate stay exactly 0 (no drift to correct).
  dydt[idx::gap] = mode == ContactMode::flight ? y[idx::gap_rate] : 0.0;
  dydt[idx::gap_rate] = mode == ContactMode::flight ? dyn.a_m.z() : 0.0;
  dydt[idx::psi] = dyn.psi_dot;
}

void jacobian_difference_steps(const Model& model, ContactMode mode, const StateVector& y, StateVector& max_step) {
  max_step.fill(0.0);
  // Nothing depends on the gap; in contact nothing depends on the gap rate either.
  max_step[idx::gap] = -1.0;
  if (mode != ContactMode::flight) max_step[idx::gap_rate] = -1.0;
  const ContactKinematics k = contact_kinematics(model, in_plane_velocity(y), angular_velocity(y));
  const double width = 1e-4 * std::max(k.v_t.norm(), model.regularization_speed);
  max_step[idx::u] = max_step[idx::u + 1] = width;
  const double R = model.top.tip_radius;
  if (R > 0.0) max_step[idx::omega] = max_step[idx::omega + 1] = width / R;  // v_t = u - R omega x n
}

bool margins_from_record(const Model& model, ContactMode mode, const StateVector& y, const ContactForceRecord& r,
                         double cos_max_tilt, ModeMargins& mg) {
  mg = ModeMargins{};
  if (mode != ContactMode::flight && model.top.com_offset != 0.0)
    mg.tilt = figure_axis(y).normalized().z() - cos_max_tilt;
  switch (mode) {
    case ContactMode::slipping:
      mg.lift = r.force.z();
      mg.painleve = r.painleve;
      return !(static_friction(model) > 0.0 && has_contact_modes(model));  // else the stick function is missing
    case ContactMode::rolling:
      mg.lift = r.force.z();
      mg.transfer = (static_friction(model) * r.force.z() - std::hypot(r.force.x(), r.force.y())) /
                    (model.top.mass * model.plane.gravity);
      return true;
    case ContactMode::flight:
      mg.lift = y[idx::gap];
      return true;
  }
  return false;
}

void model_derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                      ContactForceRecord* record) {
  if (model.kind == ModelKind::adiabatic)
    adiabatic_derivative(model, y, dydt);
  else
    derivative(model, mode, y, dydt, record);
}

}  // namespace top_sim
