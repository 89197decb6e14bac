// One contact shape's motion in the contact modes of physics.md section 9, with the shape's lowest point as the
// lever (section 13).
#include "shape_motion.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "top_sim/finite_contact.hpp"
#include "top_sim/friction.hpp"
#include "orientation.hpp"
#include "patch_law.hpp"
#include "rigid_body.hpp"

namespace top_sim {

namespace {

// The body's kernel (rigid_body.hpp): a body of shapes has no rotor, so I' = I.
using detail::cross_response;
using detail::free_motion;
using detail::FreeMotion;
using detail::inverse_inertia_times;

// The slip of section 3 and the friction direction: u is the contact point's own velocity v_cm + r_k', and the
// rolling speed the part of it the rotation carries, |r_k' - w x r_k| (R |w x n| for a sphere).
// Returns the slip's denominator |u| + rolling speed + v_eps (a patch adds its pivoting speed to it).
double slip_and_friction(const Model& model, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& w, const ShapePoint& p,
                         ShapeMotion& out, Eigen::Vector3d& t_hat) {
  const double v_eps = model.regularization_speed;
  const Eigen::Vector3d v_c = v_cm + w.cross(p.r), u = v_cm + p.r_rate, rolling = p.r_rate - w.cross(p.r);
  out.v_t = Eigen::Vector3d(v_c.x(), v_c.y(), 0.0);
  const double vt = safe_norm(out.v_t);
  const double speed_sum = std::hypot(u.x(), u.y()) + std::hypot(rolling.x(), rolling.y()) + v_eps;
  out.slip = vt / speed_sum;
  t_hat = out.v_t / regularized_norm(vt, v_eps);
  return speed_sum;
}

// d/dt v_c's bias b = -(g + r x I^-1 G + w x r') at one contact.
Eigen::Vector3d response_bias(const FreeMotion& free, const ShapePoint& p, const Eigen::Vector3d& w) {
  return -(free.g + p.r.cross(free.Ii_G) + w.cross(p.r_rate));
}

// One shape slipping on its patch (physics.md section 12 at the shape's lowest point): F = N d with
// d = n - (F_t per N |v_t|) v_t and the drilling couple N M_n n, which moves the contact by -r x I^-1 (M_n n) per
// newton of N. A Hertz patch depends on N: a first pass takes a from the weight's normal part, the second from that
// pass's N (as the tip sphere's, dynamics.cpp). Sets force, N, mu, slip, Painleve, the drilling torque and the
// contact's dissipation. `g` is the centre of mass's free acceleration (gravity and air).
void slipping_on_patch(const Model& model, const ContactShape& shape, const Eigen::Matrix3d& K,
                       const Eigen::Vector3d& b, const Eigen::Vector3d& g, const Eigen::Vector3d& w,
                       const Eigen::Vector3d& f_hat, double speed_sum, ShapeMotion& out) {
  const FiniteContact& fc = model.finite_contact;
  const Eigen::Vector3d r_x_Ii_n = out.point.r.cross(inverse_inertia_times(model.top, f_hat, Eigen::Vector3d::UnitZ()));
  const double vt = out.v_t.norm(), omega_n = w.z();
  double N = -model.top.mass * g.z();
  PatchLaw law;
  for (int pass = fc.hertz ? 0 : 1; pass < 2; ++pass) {
    out.patch_radius = shape_patch_radius(fc, shape, N);
    law = patch_law(model, drilling_lever(fc.pressure, out.patch_radius), vt, omega_n, speed_sum);
    const Eigen::Vector3d d = Eigen::Vector3d::UnitZ() - law.force_per_speed * out.v_t;
    const double n_Kd = K.row(2).dot(d) - law.drilling * r_x_Ii_n.z();
    out.painleve = model.top.mass * n_Kd;
    N = b.z() / n_Kd;
    out.force = N * d;
  }
  out.normal_force = N;
  out.mu = law.mu;
  out.slip = law.slip;
  out.drilling_torque = N * law.drilling;
  out.dissipation = N * law.force_per_speed * out.v_t.squaredNorm() - out.drilling_torque * omega_n;
}

// One shape stuck on its patch (section 12's stuck patch at the shape's lowest point, stuck_patch_force).
void stuck_on_patch(const Model& model, const ContactShape& shape, const Eigen::Matrix3d& K, const Eigen::Vector3d& b,
                    const Eigen::Vector3d& Ii_G, const Eigen::Vector3d& tau_r, const Eigen::Vector3d& f_hat,
                    ShapeMotion& out) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Vector4d x = stuck_patch_force(K, out.point.r, inverse_inertia_times(model.top, f_hat, n),
                                              n.dot(inverse_inertia_times(model.top, f_hat, tau_r)), b, n.dot(Ii_G));
  out.force = x.head<3>();
  out.normal_force = out.force.z();
  out.mu = out.normal_force > 0.0 ? std::hypot(out.force.x(), out.force.y()) / out.normal_force : 0.0;
  out.drilling_torque = x[3];
  out.patch_radius = shape_patch_radius(model.finite_contact, shape, out.normal_force);
}

}  // namespace

double shape_patch_radius(const FiniteContact& contact, const ContactShape& shape, double normal_force) {
  if (contact.hertz && shape.kind == ShapeKind::rim) return 0.0;  // a sharp edge: Hertz's radius of curvature is 0
  return patch_radius(contact, shape.radius, normal_force);
}

ShapeMotion shape_motion(const Model& model, const ContactShape& shape, ContactMode mode, const Eigen::Vector3d& v_cm,
                         const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Top& top = model.top;
  const ShapePoint p = shape_point(shape, f_hat, w);
  const FreeMotion free = free_motion(model, v_cm, f_hat, w);
  const Eigen::Vector3d b = response_bias(free, p, w);
  Eigen::Vector3d t_hat;
  ShapeMotion out;
  out.point = p;
  const double speed_sum = slip_and_friction(model, v_cm, w, p, out, t_hat);
  // Rolling resistance (section 12): the couple N tau_r adds -r x I^-1 tau_r to d/dt v_k per newton of N.
  const double delta = mode == ContactMode::flight ? 0.0 : model.finite_contact.rolling_resistance;
  const Eigen::Vector3d tau_r = delta > 0.0 ? rolling_resistance_per_newton(delta, w) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d K = cross_response(top, f_hat, p.r, p.r);
  if (delta > 0.0) K.col(2) -= p.r.cross(inverse_inertia_times(top, f_hat, tau_r));
  if (mode == ContactMode::slipping && model.finite_contact.has_patch()) {
    slipping_on_patch(model, shape, K, b, free.g, w, f_hat, speed_sum, out);
  } else if (mode == ContactMode::slipping) {
    out.mu = friction_coefficient(model.friction, out.slip);
    const Eigen::Vector3d d = Eigen::Vector3d::UnitZ() - out.mu * t_hat;
    const double n_Kd = K.row(2).dot(d);
    out.painleve = top.mass * n_Kd;
    out.normal_force = b.z() / n_Kd;
    out.force = out.normal_force * d;
    out.dissipation = out.mu * out.normal_force * t_hat.dot(out.v_t);
  } else if (mode == ContactMode::rolling && model.finite_contact.has_patch()) {
    stuck_on_patch(model, shape, K, b, free.Ii_G, tau_r, f_hat, out);
  } else if (mode == ContactMode::rolling) {
    out.force = delta > 0.0 ? Eigen::Vector3d(K.partialPivLu().solve(b)) : Eigen::Vector3d(K.llt().solve(b));
    out.normal_force = out.force.z();
    out.mu = out.normal_force > 0.0 ? std::hypot(out.force.x(), out.force.y()) / out.normal_force : 0.0;
  }
  out.a_cm = free.g + out.force / top.mass;
  const Eigen::Vector3d couple = out.normal_force * tau_r + Eigen::Vector3d(0.0, 0.0, out.drilling_torque);
  out.omega_dot = inverse_inertia_times(top, f_hat, p.r.cross(out.force) + couple) - free.Ii_G;
  // A stuck patch does no work but on a residual pivoting (omega_n ~ 0); the slipping patch's is in out already.
  if (mode == ContactMode::rolling) out.dissipation -= out.drilling_torque * w.z();
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

namespace {

// Both contacts stuck: equal and opposite forces along the line between them move nothing, so the friction split is
// open; the one that asks the least of the friction, min over lambda of max_k |F_tk| / N_k with F_t0 + lambda e and
// F_t1 - lambda e (e the line's direction, in the plane), is taken (a convex function of lambda: ternary search).
void balance_friction(TwoShapeMotion& out) {
  if (!(out.normal_force[0] > 0.0 && out.normal_force[1] > 0.0)) return;
  Eigen::Vector3d e = out.point[1].r - out.point[0].r;
  e.z() = 0.0;
  if (!(e.norm() > 0.0)) return;
  e.normalize();
  const auto demand = [&](double lambda) {
    const Eigen::Vector3d f0 = out.force[0] + lambda * e, f1 = out.force[1] - lambda * e;
    return std::max(std::hypot(f0.x(), f0.y()) / out.normal_force[0], std::hypot(f1.x(), f1.y()) / out.normal_force[1]);
  };
  const double bound = out.force[0].head<2>().norm() + out.force[1].head<2>().norm();
  double lo = -bound, hi = bound;
  for (int i = 0; i < 100 && hi - lo > 1e-14 * (bound + 1e-300); ++i) {
    const double a = lo + (hi - lo) / 3.0, b = hi - (hi - lo) / 3.0;
    if (demand(a) <= demand(b)) hi = b; else lo = a;
  }
  const double lambda = 0.5 * (lo + hi);
  out.force[0] += lambda * e;
  out.force[1] -= lambda * e;
}

// A pair with a stuck contact (section 9 at two contacts): unknowns F_k of a stuck contact, N_k of a
// slipping one (F_k = N_k d_k); rows all of v_k' = 0 stuck, n . v_k' = 0 slipping. F = B z, rows C: (C K B) z = C b,
// least-norm where both are stuck (the free rotation about the line between the contacts leaves one part open).
void stuck_pair(const Model& model, const FreeMotion& free, const Eigen::Vector3d& tau_r,
                const std::array<ContactMode, 2>& modes, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& f_hat,
                const Eigen::Vector3d& w, TwoShapeMotion& out) {
  const Top& top = model.top;
  const Eigen::Vector3d Ii_tau = inverse_inertia_times(top, f_hat, tau_r);
  Eigen::Matrix<double, 6, 6> K;
  Eigen::Matrix<double, 6, 1> b;
  pair_response(top, f_hat, w, free, out.point, Ii_tau, K, b);
  Eigen::Matrix<double, 6, Eigen::Dynamic> B = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 0);
  Eigen::Matrix<double, Eigen::Dynamic, 6> C = Eigen::Matrix<double, Eigen::Dynamic, 6>::Zero(0, 6);
  for (int k = 0; k < 2; ++k) {
    ShapeMotion one;
    Eigen::Vector3d t_hat;
    slip_and_friction(model, v_cm, w, out.point[k], one, t_hat);
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
  }
  if (modes[0] == ContactMode::rolling && modes[1] == ContactMode::rolling) balance_friction(out);
  for (int k = 0; k < 2; ++k) {
    if (modes[k] == ContactMode::slipping)
      out.dissipation -= out.force[k].dot(out.v_t[k]);  // mu N t_hat . v_t
    else if (out.normal_force[k] > 0.0)
      out.mu[k] = std::hypot(out.force[k].x(), out.force[k].y()) / out.normal_force[k];
  }
  const double N = out.normal_force[0] + out.normal_force[1];
  out.omega_dot =
      inverse_inertia_times(top, f_hat, out.point[0].r.cross(out.force[0]) + out.point[1].r.cross(out.force[1])) +
                  N * Ii_tau - free.Ii_G;
}

}  // namespace

namespace {

// Both contacts slipping, the Simulator's two-contact mode: F_k = N_k d_k, d_k = n - (F_t per N |v_t|)_k v_tk, and
// N_k N c_k the couples per newton at contact k (rolling resistance, the patch's drilling). The two normal rows give
// A N = (n . b_1, n . b_2), A_kj = n . (K_kj d_j - r_k x I^-1 c_j): a 2x2 solve. A Hertz patch depends on N_k: a
// first pass as point contacts gives the N_k that size the patches of the second (as the tip sphere's two passes).
void both_slipping(const Model& model, const std::array<ContactShape, 2>& shapes, const FreeMotion& free,
                   const Eigen::Vector3d& tau_r, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& f_hat,
                   const Eigen::Vector3d& w, TwoShapeMotion& out) {
  const Top& top = model.top;
  const FiniteContact& fc = model.finite_contact;
  const bool patch = fc.has_patch();
  std::array<Eigen::Vector3d, 2> t_hat, d, Ii_rxd;
  std::array<double, 2> speed_sum{}, rhs{}, force_per_speed{}, drilling{};
  for (int k = 0; k < 2; ++k) {
    ShapeMotion one;
    speed_sum[k] = slip_and_friction(model, v_cm, w, out.point[k], one, t_hat[k]);
    out.v_t[k] = one.v_t;
    out.slip[k] = one.slip;
    rhs[k] = response_bias(free, out.point[k], w).z();
  }
  const Eigen::Vector3d Ii_n = inverse_inertia_times(top, f_hat, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d Ii_tau = inverse_inertia_times(top, f_hat, tau_r);
  Eigen::Matrix2d A;
  for (int pass = fc.hertz ? 0 : 1; pass < 2; ++pass) {
    for (int k = 0; k < 2; ++k) {
      if (patch) {
        out.patch_radius[k] = !fc.hertz ? fc.patch_radius
                              : pass == 0 ? 0.0
                                          : shape_patch_radius(fc, shapes[k], out.normal_force[k]);
        const PatchLaw law = patch_law(model, drilling_lever(fc.pressure, out.patch_radius[k]), out.v_t[k].norm(),
                                       w.z(), speed_sum[k]);
        out.mu[k] = law.mu;
        out.slip[k] = law.slip;
        force_per_speed[k] = law.force_per_speed;
        drilling[k] = law.drilling;
        d[k] = Eigen::Vector3d::UnitZ() - law.force_per_speed * out.v_t[k];
      } else {
        out.mu[k] = friction_coefficient(model.friction, out.slip[k]);
        d[k] = Eigen::Vector3d::UnitZ() - out.mu[k] * t_hat[k];
      }
      Ii_rxd[k] = inverse_inertia_times(top, f_hat, out.point[k].r.cross(d[k])) + Ii_tau + drilling[k] * Ii_n;
    }
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j) A(k, j) = d[j].z() / top.mass - out.point[k].r.cross(Ii_rxd[j]).z();
    const double det = A.determinant(), scale = A(0, 0) * A(1, 1) + std::abs(A(0, 1) * A(1, 0));
    // Past the Painleve boundary N is meaningless; keep it finite so the fault can be located.
    const double safe = std::abs(det) > 1e-12 * scale ? det : std::copysign(1e-12 * scale + 1e-300, det);
    out.normal_force[0] = (A(1, 1) * rhs[0] - A(0, 1) * rhs[1]) / safe;
    out.normal_force[1] = (A(0, 0) * rhs[1] - A(1, 0) * rhs[0]) / safe;
  }
  out.painleve = top.mass * std::min({A(0, 0), A(1, 1), A.determinant() / (A(0, 0) + A(1, 1))});
  out.omega_dot = -free.Ii_G;
  for (int k = 0; k < 2; ++k) {
    const double N = out.normal_force[k];
    out.force[k] = N * d[k];
    out.drilling_torque[k] = N * drilling[k];
    out.omega_dot += N * Ii_rxd[k];
    out.dissipation += patch ? N * force_per_speed[k] * out.v_t[k].squaredNorm() - out.drilling_torque[k] * w.z()
                             : -out.force[k].dot(out.v_t[k]);  // mu N t_hat . v_t
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
  TwoShapeMotion out;
  out.point = p;
  if (modes[0] == ContactMode::slipping && modes[1] == ContactMode::slipping) {
    both_slipping(model, shapes, free, tau_r, v_cm, f_hat, w, out);
  } else {
    if (model.finite_contact.has_patch())
      throw std::invalid_argument("two_shape_motion: a patch at two contacts is modelled with both slipping only");
    stuck_pair(model, free, tau_r, modes, v_cm, f_hat, w, out);
  }
  const double N = out.normal_force[0] + out.normal_force[1];
  out.a_cm = free.g + (out.force[0] + out.force[1]) / top.mass;
  out.dissipation += free.air_power - N * tau_r.dot(w);
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

double free_shape_gap_rate(const Model& model, const StateVector& y) {
  std::size_t shape;
  free_shape_gap(model, y, shape);
  return shape == kNoShape ? 0.0 : shape_gap_rate(model, y, model.shapes.shape[shape]);
}

void apply_shape_impulse(const Model& model, std::size_t shape, const Eigen::Vector3d& P, StateVector& y,
                         double torsion) {
  const BodyView b = body_view(model, y);
  const Eigen::Vector3d r = shape_point(model.shapes.shape[shape], b.f_hat, b.w).r;
  const Eigen::Vector3d r_touching = shape_point(touching_shape(model), b.f_hat, b.w).r;
  // dv_cm = P / m, I d omega = r x P + Q n (a patch's torsional impulse); u = v_cm - f omega x f_hat; gap_rate is
  // the touching shape's n . v_k.
  const Eigen::Vector3d d_omega =
      inverse_inertia_times(model.top, b.f_hat, r.cross(P) + Eigen::Vector3d(0.0, 0.0, torsion));
  const Eigen::Vector3d d_u =
      detail::reference_velocity_change(model.top.mass, model.top.com_offset, b.f_hat, P, d_omega);
  y[idx::u] += d_u.x();
  y[idx::u + 1] += d_u.y();
  y[idx::gap_rate] += (P / model.top.mass + d_omega.cross(r_touching)).z();
  for (int i = 0; i < 3; ++i) y[idx::omega + i] += d_omega[i];
}

void apply_shape_stick_impulse(const Model& model, StateVector& y) {
  const BodyView b = body_view(model, y);
  const Eigen::Vector3d r = shape_point(touching_shape(model), b.f_hat, b.w).r;
  const Eigen::Vector4d x = stuck_patch_impulse(cross_response(model.top, b.f_hat, r, r), r,
                                                inverse_inertia_times(model.top, b.f_hat, Eigen::Vector3d::UnitZ()),
                                                b.v_cm + b.w.cross(r), b.w.z());
  apply_shape_impulse(model, model.shapes.touching, x.head<3>(), y, x[3]);
}

double touching_patch_radius(const Model& model, double normal_force) {
  return shape_patch_radius(model.finite_contact, touching_shape(model), normal_force);
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
  const Eigen::Vector3d centripetal = b.w.cross(b.w.cross(b.f_hat));
  const Eigen::Vector3d a_m = detail::reference_acceleration(r.a_cm, f, b.f_hat, r.omega_dot, centripetal);
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
  const auto mode = [&](int k) { return model.shapes.stuck[k] ? ContactMode::rolling : ContactMode::slipping; };
  return touching_pair_motion(model, y, {mode(0), mode(1)});
}

TwoShapeMotion touching_pair_motion(const Model& model, const StateVector& y, const std::array<ContactMode, 2>& modes) {
  const BodyView b = body_view(model, y);
  const ShapeSet& s = model.shapes;
  return two_shape_motion(model, {s.shape[s.touching], s.shape[s.second]}, modes, b.v_cm, b.f_hat, b.w);
}

double pair_contact_margin(const Model& model, const StateVector& y, const TwoShapeMotion& m, int k) {
  const double mg = model.top.mass * model.plane.gravity, mu_s = static_friction(model);
  const auto stick_set = [&](const TwoShapeMotion& pair) {
    return (mu_s * pair.normal_force[k] - std::hypot(pair.force[k].x(), pair.force[k].y())) / mg;
  };
  if (model.shapes.stuck[k]) return stick_set(m);
  std::array<ContactMode, 2> modes{model.shapes.stuck[0] ? ContactMode::rolling : ContactMode::slipping,
                                   model.shapes.stuck[1] ? ContactMode::rolling : ContactMode::slipping};
  modes[k] = ContactMode::rolling;
  return std::max(m.v_t[k].norm() / model.contact.stick_speed - 1.0, -stick_set(touching_pair_motion(model, y, modes)));
}

void apply_pair_stick_impulse(const Model& model, StateVector& y, int k) {
  const ShapeSet& s = model.shapes;
  const std::array<std::size_t, 2> shape{s.touching, s.second};
  const int j = 1 - k;
  // Unknowns: P_k (3), and P_j (3) where j is stuck, else lambda_j along n; rows: v_k+ = 0, and v_j+ = 0 or
  // n . v_j+ = 0. Columns of the pair's response K_ab (d v_a per newton-second at b).
  const int nj = s.stuck[j] ? 3 : 1;
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  const Eigen::Vector3d v_k = shape_contact_velocity(model, y, shape[k]), v_j = shape_contact_velocity(model, y, shape[j]);
  const Eigen::Matrix3d K_kk = shape_pair_response(model, y, shape[k], shape[k]);
  const Eigen::Matrix3d K_kj = shape_pair_response(model, y, shape[k], shape[j]);
  const Eigen::Matrix3d K_jk = shape_pair_response(model, y, shape[j], shape[k]);
  const Eigen::Matrix3d K_jj = shape_pair_response(model, y, shape[j], shape[j]);
  A.block<3, 3>(0, 0) = K_kk;
  rhs.head<3>() = -v_k;
  if (nj == 3) {
    A.block<3, 3>(0, 3) = K_kj;
    A.block<3, 3>(3, 0) = K_jk;
    A.block<3, 3>(3, 3) = K_jj;
    rhs.segment<3>(3) = -v_j;
  } else {
    A.block<3, 1>(0, 3) = K_kj.col(2);
    A.block<1, 3>(3, 0) = K_jk.row(2);
    A(3, 3) = K_jj(2, 2);
    rhs(3) = -v_j.z();
  }
  const int n = 3 + nj;
  // Both stuck: impulses along the line between the contacts move nothing; the least-norm pair is taken.
  const Eigen::VectorXd x = A.topLeftCorner(n, n).completeOrthogonalDecomposition().solve(rhs.head(n));
  apply_shape_impulse(model, shape[k], x.head<3>(), y);
  apply_shape_impulse(model, shape[j], nj == 3 ? Eigen::Vector3d(x.segment<3>(3)) : Eigen::Vector3d(0.0, 0.0, x(3)), y);
}

void shape_derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                      ContactForceRecord* record, ShapeMotion* motion) {
  const BodyView b = body_view(model, y);
  if (mode != ContactMode::flight && two_touching(model.shapes)) [[unlikely]] {
    const TwoShapeMotion m = touching_pair_motion(model, y);
    if (record) {  // the margins read the contact nearer to lifting off (lift = its N)
      const int nearer = m.normal_force[1] < m.normal_force[0] ? 1 : 0;
      record->force = m.force[nearer];
      record->drilling_torque = m.drilling_torque[nearer];
      record->painleve = m.painleve;
    }
    write_derivative(model, mode, y, b, {m.a_cm, m.omega_dot, m.dissipation}, m.point[0], dydt);
    return;
  }
  const ShapeMotion m = shape_motion(model, touching_shape(model), mode, b.v_cm, b.f_hat, b.w);
  if (record) {
    record->force = m.force;
    record->drilling_torque = m.drilling_torque;
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
  return detail::body_kinetic_energy(model.top, v_cm, f_hat, w) - model.top.mass * model.plane.g_plane.dot(r_cm);
}

}  // namespace top_sim
