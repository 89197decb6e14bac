// One contact shape's motion in the contact modes of physics.md section 9, with the shape's lowest point as the
// lever (section 13).
#include "top_sim/shape_motion.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>

#include "top_sim/friction.hpp"

namespace top_sim {

namespace {

// I^-1 v for the axisymmetric inertia about f_hat.
Eigen::Vector3d inverse_inertia(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& v) {
  const double inv_d = 1.0 / top.inertia_transverse, inv_f = 1.0 / top.inertia_axial;
  return inv_d * v + (inv_f - inv_d) * f_hat.dot(v) * f_hat;
}

// K = (1/m) 1 - [r]x I^-1 [r]x, column by column: d/dt v_c per newton at the contact.
Eigen::Matrix3d response_matrix(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& r) {
  Eigen::Matrix3d K;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(j);
    K.col(j) = unit / top.mass - r.cross(inverse_inertia(top, f_hat, r.cross(unit)));
  }
  return K;
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

}  // namespace

ShapeMotion shape_motion(const Model& model, const ContactShape& shape, ContactMode mode, const Eigen::Vector3d& v_cm,
                         const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Top& top = model.top;
  const Eigen::Vector3d& g = model.plane.g_plane;
  const ShapePoint p = shape_point(shape, f_hat, w);
  const Eigen::Vector3d L = top.inertia_transverse * w + (top.inertia_axial - top.inertia_transverse) * w.dot(f_hat) * f_hat;
  const Eigen::Vector3d Ii_G = inverse_inertia(top, f_hat, w.cross(L));
  // d/dt v_c = K F - b: b = -(g + r x I^-1 G + w x r')
  const Eigen::Vector3d b = -(g + p.r.cross(Ii_G) + w.cross(p.r_rate));
  Eigen::Vector3d t_hat;
  ShapeMotion out;
  slip_and_friction(model, v_cm, w, p, out, t_hat);
  if (mode == ContactMode::slipping) {
    out.mu = friction_coefficient(model.friction, out.slip);
    const Eigen::Vector3d d = Eigen::Vector3d::UnitZ() - out.mu * t_hat;
    const double n_Kd = response_matrix(top, f_hat, p.r).row(2).dot(d);
    out.painleve = top.mass * n_Kd;
    out.normal_force = b.z() / n_Kd;
    out.force = out.normal_force * d;
    out.dissipation = out.mu * out.normal_force * t_hat.dot(out.v_t);
  } else if (mode == ContactMode::rolling) {
    out.force = response_matrix(top, f_hat, p.r).llt().solve(b);
    out.normal_force = out.force.z();
    out.mu = out.normal_force > 0.0 ? std::hypot(out.force.x(), out.force.y()) / out.normal_force : 0.0;
  }
  out.a_cm = g + out.force / top.mass;
  out.omega_dot = inverse_inertia(top, f_hat, p.r.cross(out.force)) - Ii_G;
  return out;
}

double shape_body_energy(const Model& model, const Eigen::Vector3d& r_cm, const Eigen::Vector3d& v_cm,
                         const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const Top& top = model.top;
  const double w_f = w.dot(f_hat);
  const double rotation = top.inertia_transverse * (w.squaredNorm() - w_f * w_f) + top.inertia_axial * w_f * w_f;
  return 0.5 * top.mass * v_cm.squaredNorm() + 0.5 * rotation - top.mass * model.plane.g_plane.dot(r_cm);
}

}  // namespace top_sim
