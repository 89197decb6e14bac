// Internal: the one rigid-body kernel of the axisymmetric top (physics.md sections 4, 6, 9 and 12): its inverse
// inertia, torque-free part, free motion (gravity and air) and contact response, used by the tip sphere and every
// contact shape (one or a pair) alike. Inline: the right-hand side evaluates them in its hot path. Each function
// keeps the floating-point order its callers had, so that every run stays the same to the bit.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "top_sim/finite_contact.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {
namespace detail {

// 1/I_d and 1/I_f' about the figure axis (I_f' the shell's: the whole body's where there is no rotor).
struct InverseInertia {
  double d = 0.0, f = 0.0;
};
inline InverseInertia inverse_inertia(const Top& top) {
  return {1.0 / top.inertia_transverse, 1.0 / shell_axial_inertia(top)};
}

// I'^-1 v for the axisymmetric inertia about f_hat: closed form, no 3x3 solve.
inline Eigen::Vector3d inverse_inertia_times(const InverseInertia& inv, const Eigen::Vector3d& f_hat,
                                             const Eigen::Vector3d& v) {
  return inv.d * v + (inv.f - inv.d) * f_hat.dot(v) * f_hat;
}
inline Eigen::Vector3d inverse_inertia_times(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& v) {
  return inverse_inertia_times(inverse_inertia(top), f_hat, v);
}

// Section 6: L_total = I' omega + J Omega f_hat, Omega = w_f + nu the rotor's spin (J = 0 without a rotor).
inline Eigen::Vector3d total_angular_momentum(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w,
                                              double nu) {
  const double J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double I_d = top.inertia_transverse, w_f = w.dot(f_hat);
  return I_d * w + ((shell_axial_inertia(top) - I_d) * w_f + J * (w_f + nu)) * f_hat;
}

// I'^-1 G, G = omega x L_total - c nu f_hat the torque-free part (section 6), the bearing's torque c nu with a rotor.
inline Eigen::Vector3d inverse_inertia_gyro(const Top& top, const InverseInertia& inv, const Eigen::Vector3d& f_hat,
                                            const Eigen::Vector3d& w, double nu) {
  const double c = top.has_rotor ? top.rotor.coupling : 0.0;
  return inverse_inertia_times(inv, f_hat, w.cross(total_angular_momentum(top, f_hat, w, nu)) - c * nu * f_hat);
}
// The same for a body without a rotor (a body of shapes): G = omega x I omega, without the rotor's zero terms (whose
// signed zeros would round differently).
inline Eigen::Vector3d inverse_inertia_gyro(const Top& top, const InverseInertia& inv, const Eigen::Vector3d& f_hat,
                                            const Eigen::Vector3d& w) {
  const Eigen::Vector3d L =
      top.inertia_transverse * w + (top.inertia_axial - top.inertia_transverse) * w.dot(f_hat) * f_hat;
  return inverse_inertia_times(inv, f_hat, w.cross(L));
}

// What acts on the body besides its contacts: gravity, and air (section 12: -c v_cm at the centre of mass, -k w),
// as the centre of mass's acceleration g, the torque-free part I'^-1 G less I'^-1 of air's torque, air's force and
// torque, and the power air takes (air's force and torque unset until add_air: the tip sphere's hot path reads
// them only with air).
struct FreeMotion {
  Eigen::Vector3d g, Ii_G;
  Eigen::Vector3d air_force, air_torque;
  double air_power = 0.0;
};
// Air's force joins gravity and its torque the torque-free part, so every contact solve sees it unchanged.
inline void add_air(const Air& air, double mass, const InverseInertia& inv, const Eigen::Vector3d& f_hat,
                    const Eigen::Vector3d& v_cm, const Eigen::Vector3d& w, FreeMotion& free) {
  free.air_force = -air.drag * v_cm;
  free.air_torque = -air.spin_drag * w;
  free.g += free.air_force / mass;
  free.Ii_G -= inverse_inertia_times(inv, f_hat, free.air_torque);
  free.air_power = -(free.air_force.dot(v_cm) + free.air_torque.dot(w));
}
// A body without a rotor (a body of shapes) at centre-of-mass velocity v_cm.
inline FreeMotion free_motion(const Model& model, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& f_hat,
                              const Eigen::Vector3d& w) {
  const InverseInertia inv = inverse_inertia(model.top);
  FreeMotion free{model.plane.g_plane, inverse_inertia_gyro(model.top, inv, f_hat, w), Eigen::Vector3d::Zero(),
                  Eigen::Vector3d::Zero()};
  if (model.air.active()) add_air(model.air, model.top.mass, inv, f_hat, v_cm, w, free);
  return free;
}

// [r]x, the matrix of r x.
inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& r) {
  Eigen::Matrix3d Rx;
  Rx << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return Rx;
}

// Section 9: K = (1/m) 1 - [rho]x I'^-1 [rho]x at one contact of lever rho, as matrix products (the tip sphere's).
[[gnu::always_inline]] inline Eigen::Matrix3d response_matrix(double mass, const InverseInertia& inv,
                                                              const Eigen::Vector3d& f_hat,
                                                              const Eigen::Vector3d& rho) {
  const Eigen::Matrix3d Rx = cross_matrix(rho);
  const Eigen::Matrix3d Ii = inv.d * Eigen::Matrix3d::Identity() + (inv.f - inv.d) * f_hat * f_hat.transpose();
  return Eigen::Matrix3d::Identity() / mass - Rx * Ii * Rx;
}
// K_kj = (1/m) 1 - [r_k]x I'^-1 [r_j]x: d/dt v_k per newton at contact j, column by column (the shapes' rounding;
// response_matrix is the same K for k = j in the tip sphere's).
inline Eigen::Matrix3d cross_response(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& r_k,
                                      const Eigen::Vector3d& r_j) {
  const InverseInertia inv = inverse_inertia(top);
  Eigen::Matrix3d K;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(j);
    K.col(j) = unit / top.mass - r_k.cross(inverse_inertia_times(inv, f_hat, r_j.cross(unit)));
  }
  return K;
}

// The reference point r_m = r_cm - f f_hat (the state's): its acceleration a_cm - f (omega' x f_hat + omega x
// (omega x f_hat)), `centripetal` the last part, and its velocity change under an impulse P turning omega by d_omega.
inline Eigen::Vector3d reference_acceleration(const Eigen::Vector3d& a_cm, double f, const Eigen::Vector3d& f_hat,
                                              const Eigen::Vector3d& omega_dot, const Eigen::Vector3d& centripetal) {
  return a_cm - f * (omega_dot.cross(f_hat) + centripetal);
}
inline Eigen::Vector3d reference_velocity_change(double mass, double f, const Eigen::Vector3d& f_hat,
                                                 const Eigen::Vector3d& P, const Eigen::Vector3d& d_omega) {
  return P / mass - d_omega.cross(f * f_hat);
}

// Twice the shell's rotational energy, I_d |omega_perp|^2 + I_f' w_f^2 (section 4; the rotor's J Omega^2 apart).
inline double shell_rotation_energy2(const Top& top, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w) {
  const double w_f = w.dot(f_hat);
  return top.inertia_transverse * (w.squaredNorm() - w_f * w_f) + shell_axial_inertia(top) * w_f * w_f;
}
// The kinetic energy of the body without its rotor: translation at v_cm and the shell's rotation.
inline double body_kinetic_energy(const Top& top, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& f_hat,
                                  const Eigen::Vector3d& w) {
  return 0.5 * top.mass * v_cm.squaredNorm() + 0.5 * shell_rotation_energy2(top, f_hat, w);
}

// The tip sphere's body at the state y: the kernel's quantities at its contact (lever rho = r_t - r_cm).
struct RigidBody {
  double m = 0.0, R = 0.0, f = 0.0, J = 0.0, c = 0.0, nu = 0.0;
  InverseInertia inv;
  Eigen::Vector3d f_hat, w, u, rho;  // u: tip-sphere centre velocity, 3-vector (gap rate as z)
  FreeMotion free;                   // g and I'^-1 (omega x L_total - c nu f_hat); air added by the caller
  Eigen::Vector3d centripetal;       // omega x (omega x f_hat)

  [[gnu::always_inline]] RigidBody(const Model& model, const StateVector& y) {
    const Top& top = model.top;
    m = top.mass;
    R = top.tip_radius;
    f = top.com_offset;
    J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
    c = top.has_rotor ? top.rotor.coupling : 0.0;
    nu = top.has_rotor ? y[idx::nu] : 0.0;
    f_hat = figure_axis(y).normalized();  // the state's |f_hat| drifts between renormalisations
    w = angular_velocity(y);
    u = velocity3(y);
    rho = Eigen::Vector3d(-f * f_hat.x(), -f * f_hat.y(), -R - f * f_hat.z());  // r_t - r_cm
    inv = detail::inverse_inertia(top);
    free.g = model.plane.g_plane;
    free.Ii_G = inverse_inertia_gyro(top, inv, f_hat, w, nu);
    centripetal = w.cross(w.cross(f_hat));
  }

  Eigen::Vector3d inverse_inertia(const Eigen::Vector3d& v) const { return inverse_inertia_times(inv, f_hat, v); }
  // The centre of mass's velocity.
  Eigen::Vector3d v_cm() const { return u + f * w.cross(f_hat); }
  // Adds air at the centre of mass (section 12).
  void add_air(const Model& model) { detail::add_air(model.air, m, inv, f_hat, v_cm(), w, free); }

  // Section 9: K at the tip sphere's contact.
  [[gnu::always_inline]] Eigen::Matrix3d response_matrix() const {  // inline: the rolling right-hand side's hot path
    return detail::response_matrix(m, inv, f_hat, rho);
  }
  // Section 9: b = f omega x (omega x f_hat) - g - rho x (I'^-1 (omega x L_total - c nu f_hat)).
  Eigen::Vector3d response_bias() const { return f * centripetal - free.g - rho.cross(free.Ii_G); }
  // Material velocity of the top at the contact: v_c = u - R omega x n (3-vector).
  Eigen::Vector3d contact_velocity() const { return u - R * Eigen::Vector3d(w.y(), -w.x(), 0.0); }

  // Translational accelerations under a contact force F at the contact point (F = 0 in flight), given
  // omega_dot = I'^-1 (rho x F) - I'^-1 G.
  void accelerations(const Eigen::Vector3d& F, const Eigen::Vector3d& omega_dot, Eigen::Vector3d& a_cm,
                     Eigen::Vector3d& a_m) const {
    a_cm = free.g + F / m;
    a_m = reference_acceleration(a_cm, f, f_hat, omega_dot, centripetal);
  }
};

}  // namespace detail
}  // namespace top_sim
