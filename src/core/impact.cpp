// Touchdown impact (physics.md section 9).
#include "impact.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "top_sim/contact.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/friction.hpp"
#include "shape_motion.hpp"

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

namespace {

// The sliding impulse's direction n - mu_i t_hat- at shape `shape` (section 9's mu_i).
Eigen::Vector3d sliding_direction(const Model& model, const StateVector& y, std::size_t shape) {
  const ShapeMotion m = shape_motion(model, ContactMode::flight, y, shape);
  const double v_eps = model.regularization_speed;
  const double mu_i = std::max(static_friction(model), friction_coefficient(model.friction, m.slip));
  return Eigen::Vector3d::UnitZ() - mu_i * m.v_t / std::sqrt(m.v_t.squaredNorm() + v_eps * v_eps);
}

// Plastic impulses lambda_i d_i at shapes j and k that leave both normal velocities 0; false when none with
// lambda >= 0 exists (`bad` the failing denominator or lambda).
bool shared_impulse(const Model& model, StateVector& y, std::size_t j, std::size_t k, bool frictionless, double& bad) {
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d d_j = frictionless ? n : sliding_direction(model, y, j);
  const Eigen::Vector3d d_k = frictionless ? n : sliding_direction(model, y, k);
  Eigen::Matrix2d A;
  A << n.dot(shape_pair_response(model, y, j, j) * d_j), n.dot(shape_pair_response(model, y, j, k) * d_k),
      n.dot(shape_pair_response(model, y, k, j) * d_j), n.dot(shape_pair_response(model, y, k, k) * d_k);
  const Eigen::Vector2d v_n(shape_contact_velocity(model, y, j).z(), shape_contact_velocity(model, y, k).z());
  bad = std::min({A(0, 0), A(1, 1), A.determinant()});
  if (!(bad > 0.0)) return false;
  const Eigen::Vector2d lambda = A.partialPivLu().solve(-v_n);
  // The settle rule at two shapes: k, which j's impulse would leave separating slower than v_settle, is held; its
  // impulse may then pull, by at most what changes its normal velocity by v_settle.
  bad = std::min(lambda[0], lambda[1] * A(1, 1) + model.contact.settle_speed);
  if (!(bad >= 0.0)) return false;
  apply_shape_impulse(model, j, lambda[0] * d_j, y);
  apply_shape_impulse(model, k, lambda[1] * d_k, y);
  return true;
}

}  // namespace

SecondTouchdown apply_second_touchdown(Model& model, StateVector& y, std::size_t j) {
  SecondTouchdown out;
  const std::size_t k = model.shapes.touching;
  StateVector alone = y;
  retouch(model, alone, j);  // j becomes the touching shape: section 9's impact there
  alone[idx::gap] = 0.0;
  const ImpactResult impact = apply_impact(model, alone);
  if (impact.painleve) {
    model.shapes.touching = k;
    out.painleve = true;
    out.denominator = impact.denominator;
    return out;
  }
  const double rate_k = shape_gap_rate(model, alone, model.shapes.shape[k]);
  if (rate_k >= model.contact.settle_speed) {  // k separates: j alone
    y = alone;
    out.bounced = !impact.plastic;
    return out;
  }
  model.shapes.touching = k;  // k stays the state's shape; j joins it
  out.both_tried = true;
  const double e0 = shape_mechanical_energy(model, y);
  StateVector shared = y;
  if (!shared_impulse(model, shared, j, k, false, out.denominator) ||
      shape_mechanical_energy(model, shared) > e0) {
    shared = y;
    out.frictionless = true;
    if (!shared_impulse(model, shared, j, k, true, out.denominator)) {
      if (rate_k >= 0.0) {  // no pair holds, and k leaves: j alone
        model.shapes.touching = j;  // alone's gap is j's
        y = alone;
        out = SecondTouchdown{};
        return out;
      }
      out.painleve = true;
      return out;
    }
  }
  y = shared;
  y[idx::gap_rate] = 0.0;  // k's normal velocity, 0 by the impulse (rounding aside)
  model.shapes.second = j;
  model.shapes.stuck = {false, false};  // both slip after the shared sliding impulse
  out.both = true;
  return out;
}

}  // namespace top_sim
