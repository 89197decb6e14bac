// Right-hand side of the full model in each contact mode (physics.md sections 3, 4, 6 and 9).
#include "top_sim/dynamics.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "patch_law.hpp"
#include "rigid_body.hpp"
#include "top_sim/adiabatic.hpp"
#include "angular_momentum.hpp"
#include "orientation.hpp"
#include "shape_motion.hpp"

namespace top_sim {

namespace {

// Section 4: N (1/m - f A) = -n.g + f (C - B) with A = (I'^-1 T x f_hat) . n, T the contact's torque per newton
// (rho x d on a point); equal to n.b / (n.K d) of section 9. Sets the Painleve margin m (1/m - f A).
[[gnu::always_inline]] inline double constrained_normal_force(const detail::RigidBody& b, double A, double& painleve) {
  const double B = b.free.Ii_G.cross(b.f_hat).z();
  const double denominator = 1.0 / b.m - b.f * A;
  painleve = b.m * denominator;
  // Past the Painleve boundary N is meaningless; keep it finite so the fault can be located.
  const double safe = denominator > 1e-6 / b.m ? denominator : 1e-6 / b.m;
  return (-b.free.g.z() + b.f * (b.centripetal.z() - B)) / safe;
}

// Slipping (sections 3-4): F = N d, d = n - mu t_hat, N the multiplier keeping n . a_m = 0. Sets omega_dot too
// (N I'^-1 (rho x d) - I'^-1 G), reusing I'^-1 (rho x d) from the multiplier.
void slipping_force(const Model& model, const detail::RigidBody& b, PointContactDynamics& out, double& painleve) {
  out.mu = friction_coefficient(model.friction, out.contact.slip);
  const Eigen::Vector3d d(-out.mu * out.contact.t_hat.x(), -out.mu * out.contact.t_hat.y(), 1.0);
  const Eigen::Vector3d Ii_rxd = b.inverse_inertia(b.rho.cross(d));
  double N;
  if (model.normal_force == NormalForceModel::constrained) {
    N = constrained_normal_force(b, Ii_rxd.cross(b.f_hat).z(), painleve);
  } else {
    N = -b.m * b.free.g.z();  // static approximation: N = m g cos(alpha)
    painleve = ModeMargins::kNone;
  }
  out.normal_force = N;
  out.contact_force = N * d;
  out.omega_dot = N * Ii_rxd - b.free.Ii_G;
  out.dissipation = out.mu * N * out.contact.t_hat.dot(out.contact.v_t);
}

// Rolling (section 9): F = K^-1 b keeps v_c constant; no work is done at the contact.
void rolling_contact_force(const detail::RigidBody& b, PointContactDynamics& out) {
  out.contact_force = b.response_matrix().llt().solve(b.response_bias());
  out.normal_force = out.contact_force.z();
  const double Ft = std::hypot(out.contact_force.x(), out.contact_force.y());
  out.mu = out.normal_force > 0.0 ? Ft / out.normal_force : 0.0;
  out.dissipation = 0.0;
}

// ---- finite contact (physics.md section 12) ----

// Air acts on the body, not at the contact (rigid_body.hpp); the output records its force and torque.
void add_air(const Model& model, detail::RigidBody& b, ContactDynamics& out) {
  b.add_air(model);
  out.air_force = b.free.air_force;
  out.air_torque = b.free.air_torque;
}

// Rolling resistance per newton of normal force: -delta omega_r / sqrt(|omega_r|^2 + omega_eps^2).
Eigen::Vector3d rolling_resistance_per_newton(const Model& model, const detail::RigidBody& b) {
  const double delta = model.finite_contact.rolling_resistance;
  if (delta == 0.0) return Eigen::Vector3d::Zero();
  return top_sim::rolling_resistance_per_newton(delta, b.w);
}

// Slipping on a finite contact: F = N d, couple = N (M_n n + tau_r) with the coupled law of section 12; N keeps
// n . a_m = 0 as in slipping_force, with rho x d + M_n n + tau_r in place of rho x d. A Hertz patch depends on N: a
// first pass takes a from N = m g cos(alpha) and gives N, the second takes a from that N. kExtras: rolling
// resistance and air may be on (ContactModel::finite); a patch alone compiles without them.
template <bool kExtras>
void slipping_force_finite(const Model& model, const detail::RigidBody& b, ContactDynamics& out, double& painleve) {
  const FiniteContact& fc = model.finite_contact;
  const Eigen::Vector3d& v_t = out.contact.v_t;
  const double vt = v_t.norm(), omega_n = b.w.z();
  const double speed_sum = std::sqrt(b.u.x() * b.u.x() + b.u.y() * b.u.y()) + out.contact.rolling_speed +
                           model.regularization_speed;
  const bool constrained = model.normal_force == NormalForceModel::constrained;
  const bool resisting = kExtras && fc.rolling_resistance != 0.0;
  const Eigen::Vector3d tau_r = resisting ? rolling_resistance_per_newton(model, b) : Eigen::Vector3d::Zero();
  // A of constrained_normal_force is affine in q = F_t / (N |v_t|): the inertia's f_hat part drops out of the
  // cross product with f_hat, (rho x d) x f_hat = d (rho . f_hat) - rho (d . f_hat) for d = (-q v_t, 1), and
  // M_n n adds nothing; so a pass costs no torque image.
  const double A0 = b.inv.d * (b.rho.dot(b.f_hat) - b.rho.z() * b.f_hat.z() + (resisting ? tau_r.cross(b.f_hat).z() : 0.0));
  const double A1 = b.inv.d * b.rho.z() * (v_t.x() * b.f_hat.x() + v_t.y() * b.f_hat.y());
  double N = -b.m * b.free.g.z(), a = fc.patch_radius;
  if (fc.hertz) {
    a = N > 0.0 ? hertz_patch_radius(fc, b.R, N) : 0.0;
    if (constrained) {
      const PatchLaw first = patch_law(model, drilling_lever(fc.pressure, a), vt, omega_n, speed_sum);
      N = constrained_normal_force(b, A0 + first.force_per_speed * A1, painleve);
      a = N > 0.0 ? hertz_patch_radius(fc, b.R, N) : 0.0;
    }
  }
  const PatchLaw law = patch_law(model, drilling_lever(fc.pressure, a), vt, omega_n, speed_sum);
  Eigen::Vector3d T = b.rho.cross(Eigen::Vector3d(-law.force_per_speed * v_t.x(), -law.force_per_speed * v_t.y(), 1.0));
  T.z() += law.drilling;
  if (resisting) T += tau_r;
  if (constrained)
    N = constrained_normal_force(b, A0 + law.force_per_speed * A1, painleve);
  else
    painleve = ModeMargins::kNone;
  out.mu = law.mu;
  out.contact.slip = law.slip;
  out.contact.t_hat = law.force_factor_per_speed * v_t;
  out.patch_radius = a;
  out.normal_force = N;
  out.contact_force = Eigen::Vector3d(-N * law.force_per_speed * v_t.x(), -N * law.force_per_speed * v_t.y(), N);
  out.drilling_torque = N * law.drilling;
  out.couple.z() = out.drilling_torque;
  out.omega_dot = N * b.inverse_inertia(T) - b.free.Ii_G;
  out.dissipation = N * law.force_per_speed * v_t.squaredNorm() - out.drilling_torque * omega_n;
  if (resisting) {
    out.couple += N * tau_r;
    out.dissipation -= N * tau_r.dot(b.w);
  }
}

// The stick force on a finite contact: on a patch F and M_n (stuck_patch_force, patch_law.hpp); without one
// M_n = 0 and omega_n is free.
StickForce stick_force_finite(const Model& model, const detail::RigidBody& b) {
  const Eigen::Vector3d tau_r = rolling_resistance_per_newton(model, b);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d K = b.response_matrix();
  K.col(2) -= b.rho.cross(b.inverse_inertia(tau_r));
  StickForce out;
  if (!model.finite_contact.has_patch()) {
    out.force = K.partialPivLu().solve(b.response_bias());
    return out;
  }
  const Eigen::Vector4d x = stuck_patch_force(K, b.rho, b.inverse_inertia(n), n.dot(b.inverse_inertia(tau_r)),
                                               b.response_bias(), n.dot(b.free.Ii_G));
  out.force = x.head<3>();
  out.drilling_torque = x[3];
  return out;
}

void rolling_contact_force_finite(const Model& model, const detail::RigidBody& b, ContactDynamics& out) {
  const StickForce st = stick_force_finite(model, b);
  out.contact_force = st.force;
  out.normal_force = st.force.z();
  const double Ft = std::hypot(st.force.x(), st.force.y());
  out.mu = out.normal_force > 0.0 ? Ft / out.normal_force : 0.0;
  out.patch_radius = patch_radius(model.finite_contact, b.R, out.normal_force);
  out.drilling_torque = st.drilling_torque;
  out.couple = out.normal_force * rolling_resistance_per_newton(model, b) + Eigen::Vector3d(0, 0, st.drilling_torque);
  // The stuck patch does no work; the rolling resistance and a residual pivoting (omega_n ~ 0) do.
  out.dissipation = -out.couple.dot(b.w);
}

// One mode's motion; a template so that the hot slipping path compiles without the other modes' code, and each
// contact model without the code of the richer ones (physics.md section 12).
template <ContactModel kContact>
using MotionOut = std::conditional_t<kContact == ContactModel::point, PointContactDynamics, ContactDynamics>;

// Expects out's finite-contact fields zero (a fresh ContactDynamics, or cleared by evaluate_dynamics).
template <ContactMode kMode, ContactModel kContact>
void motion(const Model& model, const StateVector& y, MotionOut<kContact>& out, double& painleve) {
  constexpr bool kFinite = kContact != ContactModel::point, kExtras = kContact == ContactModel::finite;
  detail::RigidBody b(model, y);
  if constexpr (kExtras) {
    if (model.air.active()) add_air(model, b, out);
  }
  if constexpr (kFinite && kMode == ContactMode::slipping)
    out.contact = contact_velocities(model, in_plane_velocity(y), b.w);
  else
    out.contact = contact_kinematics(model, in_plane_velocity(y), b.w);
  painleve = ModeMargins::kNone;
  if constexpr (kMode == ContactMode::slipping) {
    if constexpr (kFinite)
      slipping_force_finite<kExtras>(model, b, out, painleve);
    else
      slipping_force(model, b, out, painleve);
  } else {
    if constexpr (kMode == ContactMode::rolling) {
      if constexpr (kFinite)
        rolling_contact_force_finite(model, b, out);
      else
        rolling_contact_force(b, out);
    } else {
      out.mu = 0.0;
      out.normal_force = 0.0;
      out.contact_force.setZero();
      out.dissipation = 0.0;
    }
    if constexpr (kFinite)
      out.omega_dot = b.inverse_inertia(b.rho.cross(out.contact_force) + out.couple) - b.free.Ii_G;
    else
      out.omega_dot = b.inverse_inertia(b.rho.cross(out.contact_force)) - b.free.Ii_G;
  }
  out.friction_force = Eigen::Vector3d(out.contact_force.x(), out.contact_force.y(), 0.0);
  b.accelerations(out.contact_force, out.omega_dot, out.a_cm, out.a_m);
  if constexpr (kMode != ContactMode::flight) out.a_m.z() = 0.0;  // the contact holds n . a_m = 0
  out.nu_dot = model.top.has_rotor ? -b.c * b.nu / b.J - out.omega_dot.dot(b.f_hat) : 0.0;
  out.dissipation += b.c * b.nu * b.nu;
  if constexpr (kExtras) {
    if (model.air.active()) out.dissipation += b.free.air_power;  // -(F_air . v_cm + T_air . w)
  }
  out.psi_dot = spin_phase_rate(b.f_hat, b.w);
}

template <ContactModel kContact>
[[gnu::always_inline]] inline void evaluate_motion_in(ContactMode mode, const Model& model, const StateVector& y,
                                                      MotionOut<kContact>& out, double& painleve) {
  switch (mode) {
    case ContactMode::slipping: motion<ContactMode::slipping, kContact>(model, y, out, painleve); break;
    case ContactMode::rolling: motion<ContactMode::rolling, kContact>(model, y, out, painleve); break;
    case ContactMode::flight: motion<ContactMode::flight, kContact>(model, y, out, painleve); break;
  }
}

}  // namespace

namespace {

// A slipping contact that may stick (section 9's stick function, in weights): > 0 until its slip is below the stick
// speed and the stuck force at this state lies inside the stick set. On a patch the whole generalised slip
// w = (v_t, Rbar omega_n) must be small (section 12). For the tip sphere and a touching shape alike.
double stick_transfer_margin(const Model& model, const StateVector& y, const Eigen::Vector3d& v_t) {
  const StickForce st = stick_force(model, y);
  double w = v_t.norm();
  if (model.finite_contact.has_patch())
    w = std::hypot(w, drilling_lever(model.finite_contact.pressure, stick_patch_radius(model, st.force.z())) *
                          y[idx::omega + 2]);
  return std::max(w / model.contact.stick_speed - 1.0, -stick_margin(model, st) / (model.top.mass * model.plane.gravity));
}

// Two shapes touching: their summed force is the contact force, mu the ratio of its parts, v_t and the slip the
// touching shape's (the second's are in touching_pair_motion).
void evaluate_pair_dynamics(const Model& model, ContactMode mode, const StateVector& y, double cos_max_tilt,
                            Dynamics& out) {
  const TwoShapeMotion m = touching_pair_motion(model, y);
  StateVector dydt;
  ContactForceRecord record;
  shape_derivative(model, mode, y, dydt, &record);
  out.contact_force = m.force[0] + m.force[1];
  out.normal_force = out.contact_force.z();
  out.friction_force = Eigen::Vector3d(out.contact_force.x(), out.contact_force.y(), 0.0);
  out.mu = out.normal_force > 0.0 ? out.friction_force.norm() / out.normal_force : 0.0;
  out.omega_dot = m.omega_dot;
  out.a_cm = m.a_cm;
  out.dissipation = m.dissipation;
  out.contact.v_t = m.v_t[0];
  out.contact.slip = m.slip[0];
  out.patch_radius = m.patch_radius[0];  // the touching shape's patch; M_n about n of both
  out.drilling_torque = m.drilling_torque[0] + m.drilling_torque[1];
  out.couple.z() = out.drilling_torque;
  out.a_m = Eigen::Vector3d(dydt[idx::u], dydt[idx::u + 1], dydt[idx::gap_rate]);
  out.psi_dot = dydt[idx::psi];
  margins_from_record(model, mode, y, record, cos_max_tilt, out.margins);
}

// A body with shapes: its touching shape's motion (shape_motion.hpp), mapped onto the Dynamics every reader uses.
void evaluate_shape_dynamics(const Model& model, ContactMode mode, const StateVector& y, double cos_max_tilt,
                             Dynamics& out) {
  out = Dynamics{};
  if (mode != ContactMode::flight && two_touching(model.shapes))
    return evaluate_pair_dynamics(model, mode, y, cos_max_tilt, out);
  ShapeMotion m;
  StateVector dydt;
  shape_derivative(model, mode, y, dydt, nullptr, &m);  // the motion and the reference point's rates, once
  out.mu = m.mu;
  out.normal_force = m.normal_force;
  out.contact_force = m.force;
  out.friction_force = Eigen::Vector3d(m.force.x(), m.force.y(), 0.0);
  out.omega_dot = m.omega_dot;
  out.a_cm = m.a_cm;
  out.dissipation = m.dissipation;
  out.contact.v_t = m.v_t;
  out.contact.slip = m.slip;
  out.patch_radius = m.patch_radius;
  out.drilling_torque = m.drilling_torque;
  out.couple.z() = m.drilling_torque;
  out.a_m = Eigen::Vector3d(dydt[idx::u], dydt[idx::u + 1], dydt[idx::gap_rate]);
  out.psi_dot = dydt[idx::psi];
  const ContactForceRecord record{m.force, m.drilling_torque, m.painleve};
  if (margins_from_record(model, mode, y, record, cos_max_tilt, out.margins)) return;
  out.margins.transfer = stick_transfer_margin(model, y, m.v_t);
}

}  // namespace

void evaluate_dynamics(const Model& model, ContactMode mode, const StateVector& y, Dynamics& out) {
  evaluate_dynamics(model, mode, y, out, std::cos(model.top.max_tilt));
}

void evaluate_dynamics(const Model& model, ContactMode mode, const StateVector& y, Dynamics& out, double cos_max_tilt) {
  if (has_shapes(model)) return evaluate_shape_dynamics(model, mode, y, cos_max_tilt, out);
  // motion() expects the finite contact's fields zero: clear what an earlier evaluation left (a right-hand side
  // needs no clearing, its ContactDynamics is fresh).
  const bool point = point_contact(model);
  ContactForceRecord record;
  out.patch_radius = out.drilling_torque = 0.0;
  out.couple.setZero();
  out.air_force.setZero();
  out.air_torque.setZero();
  if (point)
    evaluate_motion_in<ContactModel::point>(mode, model, y, out, record.painleve);
  else
    evaluate_motion_in<ContactModel::finite>(mode, model, y, out, record.painleve);
  record.force = out.contact_force;
  record.drilling_torque = out.drilling_torque;
  if (margins_from_record(model, mode, y, record, cos_max_tilt, out.margins)) return;
  out.margins.transfer = stick_transfer_margin(model, y, out.contact.v_t);
}

StickForce stick_force(const Model& model, const StateVector& y) {
  if (has_shapes(model)) {  // with its rolling resistance, and on a patch its drilling torque
    const ShapeMotion m = shape_motion(model, ContactMode::rolling, y);
    return {m.force, m.drilling_torque};
  }
  if (point_contact(model)) return {rolling_force(contact_response(model, y)), 0.0};
  detail::RigidBody b(model, y);
  if (model.air.active()) b.add_air(model);
  return stick_force_finite(model, b);
}

double stick_margin(const Model& model, const StickForce& st) {
  const double mu_s = static_friction(model), N = st.force.z(), Ft = std::hypot(st.force.x(), st.force.y());
  const FiniteContact& fc = model.finite_contact;
  if (!fc.has_patch()) return mu_s * N - Ft;
  const double lever = drilling_lever(fc.pressure, stick_patch_radius(model, N));
  return top_sim::stick_margin(fc.law, fc.pressure, Ft, st.drilling_torque, mu_s, N, lever);
}

double stick_patch_radius(const Model& model, double normal_force) {
  return has_shapes(model) ? touching_patch_radius(model, normal_force)
                           : patch_radius(model.finite_contact, model.top.tip_radius, normal_force);
}

double jellett(const Model& model, const StateVector& y) {
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d arm = model.top.com_offset * f_hat + Eigen::Vector3d(0.0, 0.0, model.top.tip_radius);
  return angular_momentum(model, y).dot(arm);
}

namespace {

// Inlined into model_derivative: one call less per right-hand side.
template <ContactModel kContact>
[[gnu::always_inline]] inline void derivative_in(const Model& model, ContactMode mode, const StateVector& y,
                                                 StateVector& dydt, ContactForceRecord* record) {
  MotionOut<kContact> dyn;
  double painleve;
  evaluate_motion_in<kContact>(mode, model, y, dyn, painleve);
  if (record) {
    record->force = dyn.contact_force;
    if constexpr (kContact != ContactModel::point) record->drilling_torque = dyn.drilling_torque;
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

// The full model's right-hand side; inlined into model_derivative (one call less per right-hand side).
[[gnu::always_inline]] inline void full_derivative(const Model& model, ContactModel contact, ContactMode mode,
                                                   const StateVector& y, StateVector& dydt, ContactForceRecord* record) {
  if (contact == ContactModel::point)
    derivative_in<ContactModel::point>(model, mode, y, dydt, record);
  else if (contact == ContactModel::patch)
    derivative_in<ContactModel::patch>(model, mode, y, dydt, record);
  else if (contact == ContactModel::finite)
    derivative_in<ContactModel::finite>(model, mode, y, dydt, record);
  else
    shape_derivative(model, mode, y, dydt, record);
}

}  // namespace

void derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                ContactForceRecord* record) {
  full_derivative(model, contact_model(model), mode, y, dydt, record);
}

void jacobian_difference_steps(const Model& model, ContactMode mode, const StateVector& y, StateVector& max_step) {
  max_step.fill(0.0);
  // Nothing depends on the gap; in contact nothing depends on the gap rate either.
  max_step[idx::gap] = -1.0;
  if (mode != ContactMode::flight) max_step[idx::gap_rate] = -1.0;
  const bool shapes = has_shapes(model);
  const ContactKinematics k = shapes ? shape_kinematics(model, y)
                                     : contact_kinematics(model, in_plane_velocity(y), angular_velocity(y));
  const double width = 1e-4 * std::max(k.v_t.norm(), model.regularization_speed);
  max_step[idx::u] = max_step[idx::u + 1] = width;
  const ContactShape& touching = model.shapes.shape[model.shapes.touching];  // v_t = v_cm + w x r_k, |r_k| <= reach
  const double R = shapes ? std::abs(touching.offset) + touching.radius : model.top.tip_radius;
  if (R > 0.0) max_step[idx::omega] = max_step[idx::omega + 1] = width / R;  // v_t = u - R omega x n
  if (!shapes) return;
  // A shape's lowest point r_k moves with f_hat: v_t = v_cm + w x r_k changes by |w| reach per unit of f_hat.
  max_step[idx::omega + 2] = width / R;
  const double turn = angular_velocity(y).norm() * R;
  if (turn > 0.0) max_step[idx::f] = max_step[idx::f + 1] = max_step[idx::f + 2] = width / turn;
}

namespace {

// Two shapes touching: > 0 while the body moves or accelerates (the tilt slot's end state at_rest when < 0).
double rest_margin(const Model& model, const StateVector& y, const TwoShapeMotion& m) {
  const double reach = shapes_reach(model.shapes);
  const double speed = std::max(shape_body_com_velocity(model, y).norm(), angular_velocity(y).norm() * reach);
  const double acceleration = std::max(m.a_cm.norm(), m.omega_dot.norm() * reach);
  return std::max(speed / model.contact.stick_speed, acceleration / (kRestAcceleration * model.plane.gravity)) - 1.0;
}

// A body with shapes: in flight the least gap of its shapes is the touchdown's margin; on a rim, the tilt's sine
// above kFlatEndSine is the margin of the flat end (the end margin: its event ends the run).
[[gnu::noinline]] void shape_margins(const Model& model, ContactMode mode, const StateVector& y, ModeMargins& mg) {
  mg.end = ModeMargins::kNone;
  if (mode == ContactMode::flight) {
    for (std::size_t k = 0; k < model.shapes.count; ++k)
      mg.lift = std::min(mg.lift, shape_gap(model, y, model.shapes.shape[k]));
    return;
  }
  std::size_t free_shape;
  mg.touch = free_shape_gap(model, y, free_shape);
  if (two_touching(model.shapes)) {  // no flat end; each contact's stick or slip (both slip on patches)
    const TwoShapeMotion m = touching_pair_motion(model, y);
    mg.end = rest_margin(model, y, m);
    mg.transfer = ModeMargins::kNone;
    if (static_friction(model) > 0.0 && !model.finite_contact.has_patch())
      mg.transfer = std::min(pair_contact_margin(model, y, m, 0), pair_contact_margin(model, y, m, 1));
    return;
  }
  if (model.shapes.shape[model.shapes.touching].kind == ShapeKind::rim) {
    const double c = figure_axis(y).normalized().z();
    mg.end = std::sqrt(std::max(0.0, 1.0 - c * c)) - kFlatEndSine;
  }
}

}  // namespace

namespace {

[[gnu::always_inline]] inline bool contact_margins(const Model& model, ContactMode mode, const StateVector& y,
                                                   const ContactForceRecord& r, double cos_max_tilt, ModeMargins& mg) {
  mg = ModeMargins{};
  if (mode != ContactMode::flight && model.top.com_offset != 0.0)
    mg.end = figure_axis(y).normalized().z() - cos_max_tilt;
  switch (mode) {
    case ContactMode::slipping:
      mg.lift = r.force.z();
      mg.painleve = r.painleve;
      return !(static_friction(model) > 0.0 && has_contact_modes(model));  // else the stick function is missing
    case ContactMode::rolling:
      mg.lift = r.force.z();
      if (!model.finite_contact.has_patch())  // mu_s F_n - |F_t|: rolling resistance and air leave the cone
        mg.transfer = (static_friction(model) * r.force.z() - std::hypot(r.force.x(), r.force.y())) /
                      (model.top.mass * model.plane.gravity);
      else
        mg.transfer = stick_margin(model, StickForce{r.force, r.drilling_torque}) / (model.top.mass * model.plane.gravity);
      return true;
    case ContactMode::flight:
      mg.lift = y[idx::gap];
      return true;
  }
  return false;
}

}  // namespace

bool margins_from_record(const Model& model, ContactMode mode, const StateVector& y, const ContactForceRecord& r,
                         double cos_max_tilt, ModeMargins& mg) {
  const bool complete = contact_margins(model, mode, y, r, cos_max_tilt, mg);
  if (has_shapes(model)) [[unlikely]] {  // the tilt and touchdown margins; two contacts have no stick function
    shape_margins(model, mode, y, mg);
    return complete || (mode != ContactMode::flight && two_touching(model.shapes));
  }
  return complete;
}

void model_derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                      ContactForceRecord* record) {
  model_derivative(model, contact_model(model), mode, y, dydt, record);
}

void model_derivative(const Model& model, ContactModel contact, ContactMode mode, const StateVector& y,
                      StateVector& dydt, ContactForceRecord* record) {
  if (model.kind == ModelKind::adiabatic)
    adiabatic_derivative(model, y, dydt);
  else
    full_derivative(model, contact, mode, y, dydt, record);
}

}  // namespace top_sim
