// One contact shape's motion in the contact modes of physics.md section 9, with the shape's lowest point as the
// lever (section 13).
#include "top_sim/shape_motion.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "top_sim/finite_contact.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/orientation.hpp"

namespace top_sim {

namespace {

// I^-1 v for the axisymmetric inertia about f_hat.
Eigen::Vector3d inverse_inertia(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& v) {
  const double inv_d = 1.0 / top.inertia_transverse, inv_f = 1.0 / top.inertia_axial;
  return inv_d * v + (inv_f - inv_d) * f_hat.dot(v) * f_hat;
}

// The slip of section 3 and the friction direction: u is the contact point's own velocity v_cm + r_k', and the
// rolling speed the part of it the rotation carries, |r_k' - w x r_k| (R |w x n| for a sphere).
void slip_and_friction(const Model& model, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& w, const ShapePoint& p,
                       ShapeMotion& out, Eigen::Vector3d& t_hat) {
  const double v_eps = model.regularization_speed;
  const Eigen::Vector3d v_c = v_cm + w.cross(p.r), u = v_cm + p.r_rate, rolling = p.r_rate - w.cross(p.r);
  out.v_t = Eigen::Vector3d(v_c.x(), v_c.y(), 0.0);
  const double vt = out.v_t.norm();
  out.slip = vt / (std::hypot(u.x(), u.y()) + std::hypot(rolling.x(), rolling.y()) + v_eps);
  t_hat = out.v_t / std::sqrt(vt * vt + v_eps * v_eps);
}

// d/dt v_c's bias b = -(g + r x I^-1 G + w x r') at one contact, and I^-1 G.
Eigen::Vector3d inverse_inertia_gyro(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Eigen::Vector3d L = top.inertia_transverse * w + (top.inertia_axial - top.inertia_transverse) * w.dot(f_hat) * f_hat;
  return inverse_inertia(top, f_hat, w.cross(L));
}
// What acts on the body besides its contacts: gravity, and air (physics.md section 12: -c v_cm at the centre of
// mass, -k w), as the centre of mass's acceleration g, the torque-free part I^-1 G less I^-1 of air's torque, and
// the power air takes.
struct FreeMotion {
  Eigen::Vector3d g, Ii_G;
  double air_power = 0.0;
};
FreeMotion free_motion(const Model& model, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& f_hat,
                       const Eigen::Vector3d& w) {
  FreeMotion free{model.plane.g_plane, inverse_inertia_gyro(model.top, f_hat, w), 0.0};
  if (!model.air.active()) return free;
  const Eigen::Vector3d force = -model.air.drag * v_cm, torque = -model.air.spin_drag * w;
  free.g += force / model.top.mass;
  free.Ii_G -= inverse_inertia(model.top, f_hat, torque);
  free.air_power = -(force.dot(v_cm) + torque.dot(w));
  return free;
}

Eigen::Vector3d response_bias(const FreeMotion& free, const ShapePoint& p, const Eigen::Vector3d& w) {
  return -(free.g + p.r.cross(free.Ii_G) + w.cross(p.r_rate));
}

// K_kj = (1/m) 1 - [r_k]x I^-1 [r_j]x: d/dt v_k per newton at contact j.
Eigen::Matrix3d cross_response(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& r_k,
                               const Eigen::Vector3d& r_j) {
  Eigen::Matrix3d K;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(j);
    K.col(j) = unit / top.mass - r_k.cross(inverse_inertia(top, f_hat, r_j.cross(unit)));
  }
  return K;
}

}  // namespace

ShapeMotion shape_motion(const Model& model, const ContactShape& shape, ContactMode mode, const Eigen::Vector3d& v_cm,
                         const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Top& top = model.top;
  const ShapePoint p = shape_point(shape, f_hat, w);
  const FreeMotion free = free_motion(model, v_cm, f_hat, w);
  const Eigen::Vector3d b = response_bias(free, p, w);
  Eigen::Vector3d t_hat;
  ShapeMotion out;
  out.point = p;
  slip_and_friction(model, v_cm, w, p, out, t_hat);
  // Rolling resistance (section 12): the couple N tau_r adds -r x I^-1 tau_r to d/dt v_k per newton of N.
  const double delta = mode == ContactMode::flight ? 0.0 : model.finite_contact.rolling_resistance;
  const Eigen::Vector3d tau_r = delta > 0.0 ? rolling_resistance_per_newton(delta, w) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d K = cross_response(top, f_hat, p.r, p.r);
  if (delta > 0.0) K.col(2) -= p.r.cross(inverse_inertia(top, f_hat, tau_r));
  if (mode == ContactMode::slipping) {
    out.mu = friction_coefficient(model.friction, out.slip);
    const Eigen::Vector3d d = Eigen::Vector3d::UnitZ() - out.mu * t_hat;
    const double n_Kd = K.row(2).dot(d);
    out.painleve = top.mass * n_Kd;
    out.normal_force = b.z() / n_Kd;
    out.force = out.normal_force * d;
    out.dissipation = out.mu * out.normal_force * t_hat.dot(out.v_t);
  } else if (mode == ContactMode::rolling) {
    out.force = delta > 0.0 ? Eigen::Vector3d(K.partialPivLu().solve(b)) : Eigen::Vector3d(K.llt().solve(b));
    out.normal_force = out.force.z();
    out.mu = out.normal_force > 0.0 ? std::hypot(out.force.x(), out.force.y()) / out.normal_force : 0.0;
  }
  out.a_cm = free.g + out.force / top.mass;
  out.omega_dot = inverse_inertia(top, f_hat, p.r.cross(out.force) + out.normal_force * tau_r) - free.Ii_G;
  out.dissipation += free.air_power - out.normal_force * tau_r.dot(w);
  return out;
}

namespace {

// The pair's d/dt (v_1, v_2) = K (F_1, F_2) - b, rolling resistance's couple in K's normal columns.
void pair_response(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w, const FreeMotion& free,
                   const std::array<ShapePoint, 2>& p, const Eigen::Vector3d& Ii_tau, Eigen::Matrix<double, 6, 6>& K,
                   Eigen::Matrix<double, 6, 1>& b) {
  for (int k = 0; k < 2; ++k) {
    b.segment<3>(3 * k) = response_bias(free, p[k], w);
    for (int j = 0; j < 2; ++j) {
      K.block<3, 3>(3 * k, 3 * j) = cross_response(top, f_hat, p[k].r, p[j].r);
      K.block<3, 1>(3 * k, 3 * j + 2) -= p[k].r.cross(Ii_tau);
    }
  }
}

}  // namespace

TwoShapeMotion two_shape_motion(const Model& model, const std::array<ContactShape, 2>& shapes,
                                const std::array<ContactMode, 2>& modes, const Eigen::Vector3d& v_cm,
                                const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Top& top = model.top;
  const std::array<ShapePoint, 2> p{shape_point(shapes[0], f_hat, w), shape_point(shapes[1], f_hat, w)};
  const FreeMotion free = free_motion(model, v_cm, f_hat, w);
  // Rolling resistance (section 12) at each contact: N_j tau_r moves every contact k by -r_k x I^-1 tau_r per newton.
  const double delta = model.finite_contact.rolling_resistance;
  const Eigen::Vector3d tau_r = delta > 0.0 ? rolling_resistance_per_newton(delta, w) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d Ii_tau = inverse_inertia(top, f_hat, tau_r);
  Eigen::Matrix<double, 6, 6> K;
  Eigen::Matrix<double, 6, 1> b;
  pair_response(top, f_hat, w, free, p, Ii_tau, K, b);
  // Unknowns: F_k of a stuck contact, N_k of a slipping one (F_k = N_k d_k); rows: all of v_k' = 0 stuck, n . v_k' = 0
  // slipping. F = B z, rows C: (C K B) z = C b.
  TwoShapeMotion out;
  Eigen::Matrix<double, 6, Eigen::Dynamic> B = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 0);
  Eigen::Matrix<double, Eigen::Dynamic, 6> C = Eigen::Matrix<double, Eigen::Dynamic, 6>::Zero(0, 6);
  for (int k = 0; k < 2; ++k) {
    ShapeMotion one;
    Eigen::Vector3d t_hat;
    slip_and_friction(model, v_cm, w, p[k], one, t_hat);
    out.v_t[k] = one.v_t;
    out.slip[k] = one.slip;
    const bool stuck = modes[k] == ContactMode::rolling;
    const Eigen::Index columns = B.cols(), rows = C.rows(), width = stuck ? 3 : 1;
    B.conservativeResize(Eigen::NoChange, columns + width);
    C.conservativeResize(rows + width, Eigen::NoChange);
    B.rightCols(width).setZero();
    C.bottomRows(width).setZero();
    if (stuck) {
      B.block<3, 3>(3 * k, columns).setIdentity();
      C.block<3, 3>(rows, 3 * k).setIdentity();
    } else {
      out.mu[k] = friction_coefficient(model.friction, one.slip);
      B.block<3, 1>(3 * k, columns) = Eigen::Vector3d::UnitZ() - out.mu[k] * t_hat;
      C(rows, 3 * k + 2) = 1.0;
    }
  }
  const Eigen::MatrixXd A = C * K * B;
  const Eigen::VectorXd z = A.completeOrthogonalDecomposition().solve(C * b);
  const Eigen::Matrix<double, 6, 1> F = B * z;
  for (int k = 0; k < 2; ++k) {
    out.force[k] = F.segment<3>(3 * k);
    out.normal_force[k] = out.force[k].z();
    if (modes[k] == ContactMode::slipping)
      out.dissipation -= out.force[k].dot(out.v_t[k]);  // mu N t_hat . v_t
    else if (out.normal_force[k] > 0.0)
      out.mu[k] = std::hypot(out.force[k].x(), out.force[k].y()) / out.normal_force[k];
  }
  if (A.rows() == 2 && A.cols() == 2)
    out.painleve = top.mass * std::min({A(0, 0), A(1, 1), A.determinant() / (A(0, 0) + A(1, 1))});
  const double N = out.normal_force[0] + out.normal_force[1];
  out.a_cm = free.g + (out.force[0] + out.force[1]) / top.mass;
  out.omega_dot = inverse_inertia(top, f_hat, p[0].r.cross(out.force[0]) + p[1].r.cross(out.force[1])) + N * Ii_tau -
                  free.Ii_G;
  out.dissipation += free.air_power - N * tau_r.dot(w);
  out.point = p;
  return out;
}

namespace {

// The body's centre-of-mass quantities from the state (the reference point r_m = r_cm - f f_hat, shape_motion.hpp).
struct BodyView {
  Eigen::Vector3d v_cm, f_hat, w;
  double z_cm = 0.0;
};
const ContactShape& touching_shape(const Model& model) { return model.shapes.shape[model.shapes.touching]; }

// The state's gap and gap_rate are the touching shape's, g_k = z_cm + h_k(c) and n . v_k: z_cm = g_k - h_k(c) and
// n . v_cm = g_k' - n . (w x r_k); in-plane, v_cm = u + f w x f_hat.
BodyView body_view(const Model& model, const StateVector& y) {
  BodyView b;
  b.f_hat = figure_axis(y).normalized();
  b.w = angular_velocity(y);
  const ShapePoint p = shape_point(touching_shape(model), b.f_hat, b.w);
  b.z_cm = y[idx::gap] - p.height;
  b.v_cm = in_plane_velocity(y) + model.top.com_offset * b.w.cross(b.f_hat);
  b.v_cm.z() = y[idx::gap_rate] - b.w.cross(p.r).z();
  return b;
}

}  // namespace

Eigen::Vector3d shape_body_com(const Model& model, const StateVector& y) {
  const BodyView b = body_view(model, y);
  const Eigen::Vector3d in_plane = Eigen::Vector3d(y[idx::x], y[idx::x + 1], 0.0) + model.top.com_offset * b.f_hat;
  return {in_plane.x(), in_plane.y(), b.z_cm};
}

Eigen::Vector3d shape_body_com_velocity(const Model& model, const StateVector& y) { return body_view(model, y).v_cm; }

void retouch(Model& model, StateVector& y, std::size_t shape) {
  const BodyView b = body_view(model, y);
  model.shapes.touching = shape;
  const ShapePoint p = shape_point(touching_shape(model), b.f_hat, b.w);
  y[idx::gap] = b.z_cm + p.height;
  y[idx::gap_rate] = b.v_cm.z() + b.w.cross(p.r).z();
}

double shape_gap(const Model& model, const StateVector& y, const ContactShape& shape) {
  const BodyView b = body_view(model, y);
  return b.z_cm + shape_height(shape, b.f_hat.z());
}

double shape_gap_rate(const Model& model, const StateVector& y, const ContactShape& shape) {
  const BodyView b = body_view(model, y);
  return (b.v_cm + b.w.cross(shape_point(shape, b.f_hat, b.w).r)).z();
}

std::size_t lowest_shape(const Model& model, const StateVector& y) {
  return lowest_shape(model.shapes, figure_axis(y).normalized());
}

ContactKinematics shape_kinematics(const Model& model, const StateVector& y) {
  const BodyView b = body_view(model, y);
  const ShapePoint p = shape_point(touching_shape(model), b.f_hat, b.w);
  ShapeMotion m;
  ContactKinematics k;
  slip_and_friction(model, b.v_cm, b.w, p, m, k.t_hat);
  const Eigen::Vector3d rolling = p.r_rate - b.w.cross(p.r);
  k.v_t = m.v_t;
  k.slip = m.slip;
  k.rolling_speed = std::hypot(rolling.x(), rolling.y());
  return k;
}

std::uint32_t touching_shapes(const Model& model, ContactMode mode) {
  if (mode == ContactMode::flight) return 0;
  if (!has_shapes(model)) return 1;
  const std::uint32_t second = two_touching(model.shapes) ? std::uint32_t{1} << model.shapes.second : 0;
  return (std::uint32_t{1} << model.shapes.touching) | second;
}

double free_shape_gap(const Model& model, const StateVector& y, std::size_t& shape) {
  double least = ModeMargins::kNone;
  shape = kNoShape;
  if (model.shapes.count < 2) return least;  // one shape: it touches
  const BodyView b = body_view(model, y);
  for (std::size_t k = 0; k < model.shapes.count; ++k) {
    if (k == model.shapes.touching || k == model.shapes.second) continue;
    const double gap = b.z_cm + shape_height(model.shapes.shape[k], b.f_hat.z());
    if (gap < least) least = gap, shape = k;
  }
  return least;
}

void apply_shape_impulse(const Model& model, std::size_t shape, const Eigen::Vector3d& P, StateVector& y) {
  const BodyView b = body_view(model, y);
  const Eigen::Vector3d r = shape_point(model.shapes.shape[shape], b.f_hat, b.w).r;
  const Eigen::Vector3d r_touching = shape_point(touching_shape(model), b.f_hat, b.w).r;
  // dv_cm = P / m, I d omega = r x P; u = v_cm - f omega x f_hat; gap_rate is the touching shape's n . v_k.
  const Eigen::Vector3d d_omega = inverse_inertia(model.top, b.f_hat, r.cross(P));
  const Eigen::Vector3d d_u = P / model.top.mass - d_omega.cross(model.top.com_offset * b.f_hat);
  y[idx::u] += d_u.x();
  y[idx::u + 1] += d_u.y();
  y[idx::gap_rate] += (P / model.top.mass + d_omega.cross(r_touching)).z();
  for (int i = 0; i < 3; ++i) y[idx::omega + i] += d_omega[i];
}

Eigen::Matrix3d shape_pair_response(const Model& model, const StateVector& y, std::size_t k, std::size_t j) {
  const BodyView b = body_view(model, y);
  return cross_response(model.top, b.f_hat, shape_point(model.shapes.shape[k], b.f_hat, b.w).r,
                        shape_point(model.shapes.shape[j], b.f_hat, b.w).r);
}

Eigen::Vector3d shape_contact_velocity(const Model& model, const StateVector& y, std::size_t shape) {
  const BodyView b = body_view(model, y);
  return b.v_cm + b.w.cross(shape_point(model.shapes.shape[shape], b.f_hat, b.w).r);
}

ShapeMotion shape_motion(const Model& model, ContactMode mode, const StateVector& y) {
  return shape_motion(model, mode, y, model.shapes.touching);
}

ShapeMotion shape_motion(const Model& model, ContactMode mode, const StateVector& y, std::size_t shape) {
  const BodyView b = body_view(model, y);
  return shape_motion(model, model.shapes.shape[shape], mode, b.v_cm, b.f_hat, b.w);
}

namespace {

// The body's rates in a contact mode: a_cm, w' and the power dissipated, whatever touches.
struct BodyRates {
  Eigen::Vector3d a_cm, omega_dot;
  double dissipation = 0.0;
};

// dy/dt from the body's rates; `p` the touching shape's point (its gap's acceleration in flight).
void write_derivative(const Model& model, ContactMode mode, const StateVector& y, const BodyView& b,
                      const BodyRates& r, const ShapePoint& p, StateVector& dydt) {
  // The reference point r_m = r_cm - f f_hat in the plane: a_m = a_cm - f (w' x f_hat + w x (w x f_hat)).
  const double f = model.top.com_offset;
  const Eigen::Vector3d a_m = r.a_cm - f * (r.omega_dot.cross(b.f_hat) + b.w.cross(b.w.cross(b.f_hat)));
  // The touching shape's gap: g_k'' = n . (a_cm + w' x r_k + w x r_k') in flight (0 in contact, by the constraint).
  const double g_k_acceleration = (r.a_cm + r.omega_dot.cross(p.r) + b.w.cross(p.r_rate)).z();
  const Eigen::Vector3d f_dot = b.w.cross(figure_axis(y));  // keeps |f_hat| in the exact flow
  dydt[idx::x] = y[idx::u];
  dydt[idx::x + 1] = y[idx::u + 1];
  dydt[idx::u] = a_m.x();
  dydt[idx::u + 1] = a_m.y();
  for (int i = 0; i < 3; ++i) {
    dydt[idx::f + i] = f_dot[i];
    dydt[idx::omega + i] = r.omega_dot[i];
  }
  dydt[idx::nu] = 0.0;
  dydt[idx::w_diss] = r.dissipation;
  // In contact the touching shape's gap and its rate stay exactly 0 (no drift to correct), as the tip sphere's.
  dydt[idx::gap] = mode == ContactMode::flight ? y[idx::gap_rate] : 0.0;
  dydt[idx::gap_rate] = mode == ContactMode::flight ? g_k_acceleration : 0.0;
  dydt[idx::psi] = spin_phase_rate(b.f_hat, b.w);
}

}  // namespace

TwoShapeMotion touching_pair_motion(const Model& model, const StateVector& y) {
  const BodyView b = body_view(model, y);
  const ShapeSet& s = model.shapes;
  return two_shape_motion(model, {s.shape[s.touching], s.shape[s.second]},
                          {ContactMode::slipping, ContactMode::slipping}, b.v_cm, b.f_hat, b.w);
}

void shape_derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                      ContactForceRecord* record, ShapeMotion* motion) {
  const BodyView b = body_view(model, y);
  if (mode != ContactMode::flight && two_touching(model.shapes)) [[unlikely]] {
    const TwoShapeMotion m = touching_pair_motion(model, y);
    if (record) {  // the margins read the contact nearer to lifting off (lift = its N)
      record->force = m.force[m.normal_force[1] < m.normal_force[0] ? 1 : 0];
      record->drilling_torque = 0.0;
      record->painleve = m.painleve;
    }
    write_derivative(model, mode, y, b, {m.a_cm, m.omega_dot, m.dissipation}, m.point[0], dydt);
    return;
  }
  const ShapeMotion m = shape_motion(model, touching_shape(model), mode, b.v_cm, b.f_hat, b.w);
  if (record) {
    record->force = m.force;
    record->drilling_torque = 0.0;
    record->painleve = m.painleve;
  }
  write_derivative(model, mode, y, b, {m.a_cm, m.omega_dot, m.dissipation}, m.point, dydt);
  if (motion) *motion = m;
}

ContactResponse shape_contact_response(const Model& model, const StateVector& y) {
  const BodyView b = body_view(model, y);
  const ShapePoint p = shape_point(touching_shape(model), b.f_hat, b.w);
  ContactResponse r;
  r.K = cross_response(model.top, b.f_hat, p.r, p.r);
  r.b = response_bias(free_motion(model, b.v_cm, b.f_hat, b.w), p, b.w);
  r.rho = p.r;
  r.v_c = b.v_cm + b.w.cross(p.r);
  return r;
}

double shape_mechanical_energy(const Model& model, const StateVector& y) {
  const BodyView b = body_view(model, y);
  return shape_body_energy(model, shape_body_com(model, y), b.v_cm, b.f_hat, b.w);
}

double shape_energy_scale(const Model& model, const StateVector& y) {
  const double reach = shapes_reach(model.shapes);
  const BodyView b = body_view(model, y);
  const double kinetic = shape_body_energy(model, Eigen::Vector3d::Zero(), b.v_cm, b.f_hat, b.w);
  return kinetic + model.top.mass * model.plane.gravity * reach;
}

double shape_body_energy(const Model& model, const Eigen::Vector3d& r_cm, const Eigen::Vector3d& v_cm,
                         const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Top& top = model.top;
  const double w_f = w.dot(f_hat);
  const double rotation = top.inertia_transverse * (w.squaredNorm() - w_f * w_f) + top.inertia_axial * w_f * w_f;
  return 0.5 * top.mass * v_cm.squaredNorm() + 0.5 * rotation - top.mass * model.plane.g_plane.dot(r_cm);
}

}  // namespace top_sim
