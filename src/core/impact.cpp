// Touchdown impact (physics.md section 9).
#include "top_sim/impact.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "top_sim/contact.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/shape_motion.hpp"

namespace top_sim {

ImpactResult apply_impact(const Model& model, StateVector& y) {
  ImpactResult out;
  const ContactResponse r = contact_response(model, y);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const double vn = r.v_c.z();
  out.normal_velocity_before = vn;
  double e = model.contact.restitution;
  if (e * std::abs(vn) < model.contact.settle_speed) {  // plastic: no Zeno sequence of ever smaller bounces
    e = 0.0;
    out.plastic = true;
  }
  // s- and t_hat- from the in-plane parts only (t_hat- is defined at v_t = 0).
  ContactKinematics k;
  if (has_shapes(model)) {
    const ShapeMotion m = shape_motion(model, ContactMode::flight, y);
    k.slip = m.slip;
    k.t_hat = m.v_t / std::sqrt(m.v_t.squaredNorm() + model.regularization_speed * model.regularization_speed);
  } else {
    k = contact_kinematics(model, Eigen::Vector3d(y[idx::u], y[idx::u + 1], 0.0), angular_velocity(y));
  }
  const double mu_i = std::max(static_friction(model), friction_coefficient(model.friction, k.slip));

  // Branch 1: the sticking impulse that leaves v_c+ = -e (n . v_c-) n.
  const Eigen::Vector3d v_plus = -e * vn * n;
  Eigen::Vector3d P = r.K.llt().solve(v_plus - r.v_c);
  if (std::hypot(P.x(), P.y()) <= mu_i * P.z()) {
    out.sticking = true;
  } else {
    // Branch 2: sliding impulse P = P_n (n - mu_i t_hat-).
    const Eigen::Vector3d dir = n - mu_i * k.t_hat;
    out.denominator = n.dot(r.K * dir);
    if (!(out.denominator > 0.0)) {
      out.painleve = true;
      return out;
    }
    P = (-(1.0 + e) * vn / out.denominator) * dir;
  }
  out.impulse = P;
  apply_contact_impulse(model, P, y);
  out.normal_velocity_after = y[idx::gap_rate];  // n . v_c = n . u: the normal part of R omega x n is 0
  if (out.plastic) y[idx::gap_rate] = 0.0;       // the contact closes exactly (rounding aside it already is)
  return out;
}

}  // namespace top_sim
