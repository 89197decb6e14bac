// Contact modes (physics.md section 9): K, the rolling force, the stick impulse and the closing rule.
#include "top_sim/contact_modes.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "patch_law.hpp"
#include "rigid_body.hpp"
#include "top_sim/dynamics.hpp"
#include "shape_motion.hpp"

namespace top_sim {

const char* to_string(ContactMode mode) {
  switch (mode) {
    case ContactMode::slipping: return "slipping";
    case ContactMode::rolling: return "rolling";
    case ContactMode::flight: return "flight";
  }
  return "?";
}

const char* to_string(ModeSwitchKind kind) {
  switch (kind) {
    case ModeSwitchKind::lift_off: return "lift_off";
    case ModeSwitchKind::touchdown: return "touchdown";
    case ModeSwitchKind::stick: return "stick";
    case ModeSwitchKind::slip: return "slip";
  }
  return "?";
}

bool has_contact_modes(const Model& model) {
  return model.normal_force == NormalForceModel::constrained && model.kind == ModelKind::full;
}

ContactResponse contact_response(const Model& model, const StateVector& y) {
  if (has_shapes(model)) return shape_contact_response(model, y);
  const detail::RigidBody b(model, y);
  ContactResponse r;
  r.K = b.response_matrix();
  r.b = b.response_bias();
  r.rho = b.rho;
  r.v_c = b.contact_velocity();
  return r;
}

Eigen::Vector3d rolling_force(const ContactResponse& r) { return r.K.llt().solve(r.b); }

bool rolling_consistent(const Eigen::Vector3d& F, double static_friction) {
  return F.z() > 0.0 && std::hypot(F.x(), F.y()) <= static_friction * F.z();
}

void apply_contact_impulse(const Model& model, const Eigen::Vector3d& P, StateVector& y, double torsion) {
  if (has_shapes(model)) return apply_shape_impulse(model, model.shapes.touching, P, y, torsion);
  const detail::RigidBody b(model, y);
  // dv_cm = P / m, I' d omega = rho x P (+ the patch's torsional impulse about n); u = v_cm - omega x (f f_hat);
  // the rotor keeps its absolute spin (the bearing is viscous: no impulsive torque), so nu changes by
  // -d omega . f_hat.
  const Eigen::Vector3d d_omega = torsion == 0.0 ? b.inverse_inertia(b.rho.cross(P))
                                                 : b.inverse_inertia(b.rho.cross(P) + Eigen::Vector3d(0, 0, torsion));
  const Eigen::Vector3d d_u = detail::reference_velocity_change(b.m, b.f, b.f_hat, P, d_omega);
  set_velocity3(y, b.u + d_u);
  set_angular_velocity(y, b.w + d_omega);
  if (model.top.has_rotor) y[idx::nu] -= d_omega.dot(b.f_hat);
}

void apply_stick_impulse(const Model& model, StateVector& y) {
  if (model.finite_contact.has_patch() && has_shapes(model)) return apply_shape_stick_impulse(model, y);
  if (model.finite_contact.has_patch()) {
    // On a patch the stick also stops the pivoting: impulse P and torsional impulse Q with d v_t = -v_t and
    // d omega_n = -omega_n, through the 4x4 response of dynamics.cpp's stick force (without rolling resistance,
    // which has no impulse).
    const detail::RigidBody b(model, y);
    const Eigen::Vector4d x = stuck_patch_impulse(b.response_matrix(), b.rho, b.inverse_inertia(Eigen::Vector3d::UnitZ()),
                                                  b.contact_velocity(), b.w.z());
    apply_contact_impulse(model, x.head<3>(), y, x[3]);
    return;
  }
  const ContactResponse r = contact_response(model, y);
  // P = -K^-1 (v_t, 0): removes the tangential contact velocity and leaves n . v_c unchanged.
  const Eigen::Vector3d v_t(r.v_c.x(), r.v_c.y(), 0.0);
  apply_contact_impulse(model, -r.K.llt().solve(v_t), y);
}

bool stick_inside_cone(const Model& model, StateVector& y) {
  StateVector stuck = y;
  apply_stick_impulse(model, stuck);
  Dynamics dyn;
  evaluate_dynamics(model, ContactMode::rolling, stuck, dyn);
  if (!(dyn.margins.transfer > 0.0)) return false;
  y = stuck;
  return true;
}

ClosingResult close_contact(const Model& model, StateVector& y) {
  ClosingResult out;
  y[idx::gap] = 0.0;
  y[idx::gap_rate] = 0.0;
  if (!has_contact_modes(model)) return out;  // permanent slipping contact
  const double mu_s = static_friction(model);
  if (mu_s > 0.0) {
    const ContactResponse r = contact_response(model, y);
    double v_t = std::hypot(r.v_c.x(), r.v_c.y());
    bool holds;
    if (model.finite_contact.has_patch()) {  // physics.md section 12: the generalised slip must be small and the
      const StickForce st = stick_force(model, y);  // stick set must hold
      const double lever = drilling_lever(model.finite_contact.pressure, stick_patch_radius(model, st.force.z()));
      v_t = std::hypot(v_t, lever * y[idx::omega + 2]);
      holds = st.force.z() > 0.0 && stick_margin(model, st) >= 0.0;
    } else if (has_shapes(model)) {
      holds = rolling_consistent(shape_motion(model, ContactMode::rolling, y).force, mu_s);
    } else {
      holds = rolling_consistent(rolling_force(r), mu_s);
    }
    if (v_t <= model.contact.stick_speed && holds && stick_inside_cone(model, y)) {
      out.mode = ContactMode::rolling;
      out.stuck = true;
      return out;
    }
  }
  Dynamics dyn;
  evaluate_dynamics(model, ContactMode::slipping, y, dyn);
  if (dyn.margins.painleve <= 0.0)
    out.painleve = true;
  else if (dyn.normal_force < 0.0)
    out.mode = ContactMode::flight;
  return out;
}

ClosingResult initial_mode(const Model& model, StateVector& y) {
  if (has_contact_modes(model) && (y[idx::gap] > 0.0 || y[idx::gap_rate] > 0.0)) {
    ClosingResult out;
    out.mode = ContactMode::flight;
    return out;
  }
  return close_contact(model, y);
}

}  // namespace top_sim
