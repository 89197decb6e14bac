// Internal: the kinematic and inertial quantities every contact mode derives from the state (physics.md
// sections 4, 6 and 9). Inline: the right-hand side evaluates them once per call.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {
namespace detail {

// I'^-1 v for the axisymmetric inertia about f_hat: closed form, no 3x3 solve.
inline Eigen::Vector3d inverse_inertia_times(double inv_d, double inv_f, const Eigen::Vector3d& f_hat,
                                             const Eigen::Vector3d& v) {
  return inv_d * v + (inv_f - inv_d) * f_hat.dot(v) * f_hat;
}

struct RigidBody {
  double m = 0.0, R = 0.0, f = 0.0, J = 0.0, c = 0.0, nu = 0.0;
  double inv_d = 0.0, inv_f = 0.0;  // 1/I_d, 1/I_f'
  Eigen::Vector3d g, f_hat, w, u, rho;  // u: tip-sphere centre velocity, 3-vector (gap rate as z)
  Eigen::Vector3d Ii_G;                 // I'^-1 (omega x L_total - c nu f_hat)
  Eigen::Vector3d centripetal;          // omega x (omega x f_hat)

  [[gnu::always_inline]] RigidBody(const Model& model, const StateVector& y) {
    const Top& top = model.top;
    m = top.mass;
    R = top.tip_radius;
    f = top.com_offset;
    J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
    c = top.has_rotor ? top.rotor.coupling : 0.0;
    nu = top.has_rotor ? y[idx::nu] : 0.0;
    g = model.plane.g_plane;
    f_hat = figure_axis(y).normalized();  // the state's |f_hat| drifts between renormalisations
    w = angular_velocity(y);
    u = velocity3(y);
    rho = Eigen::Vector3d(-f * f_hat.x(), -f * f_hat.y(), -R - f * f_hat.z());  // r_t - r_cm
    const double I_d = top.inertia_transverse, I_fs = top.inertia_axial - J;  // I_f'
    inv_d = 1.0 / I_d;
    inv_f = 1.0 / I_fs;
    // Section 6: L_total = I' omega + J Omega f_hat; shell torque-free part G = omega x L_total - c nu f_hat.
    const double w_f = w.dot(f_hat);
    const Eigen::Vector3d L = I_d * w + ((I_fs - I_d) * w_f + J * (w_f + nu)) * f_hat;
    Ii_G = inverse_inertia_times(inv_d, inv_f, f_hat, w.cross(L) - c * nu * f_hat);
    centripetal = w.cross(w.cross(f_hat));
  }

  Eigen::Vector3d inverse_inertia(const Eigen::Vector3d& v) const { return inverse_inertia_times(inv_d, inv_f, f_hat, v); }

  // Section 9: K = (1/m) 1 + [rho]x^T I'^-1 [rho]x.
  [[gnu::always_inline]] Eigen::Matrix3d response_matrix() const {  // inline: the rolling right-hand side's hot path
    Eigen::Matrix3d Rx;
    Rx << 0.0, -rho.z(), rho.y(), rho.z(), 0.0, -rho.x(), -rho.y(), rho.x(), 0.0;
    const Eigen::Matrix3d Ii = inv_d * Eigen::Matrix3d::Identity() + (inv_f - inv_d) * f_hat * f_hat.transpose();
    return Eigen::Matrix3d::Identity() / m - Rx * Ii * Rx;
  }
  // Section 9: b = f omega x (omega x f_hat) - g - rho x (I'^-1 (omega x L_total - c nu f_hat)).
  Eigen::Vector3d response_bias() const { return f * centripetal - g - rho.cross(Ii_G); }
  // Material velocity of the top at the contact: v_c = u - R omega x n (3-vector).
  Eigen::Vector3d contact_velocity() const { return u - R * Eigen::Vector3d(w.y(), -w.x(), 0.0); }

  // Translational accelerations under a contact force F at the contact point (F = 0 in flight), given
  // omega_dot = I'^-1 (rho x F) - I'^-1 G.
  void accelerations(const Eigen::Vector3d& F, const Eigen::Vector3d& omega_dot, Eigen::Vector3d& a_cm,
                     Eigen::Vector3d& a_m) const {
    a_cm = g + F / m;
    a_m = a_cm - f * (omega_dot.cross(f_hat) + centripetal);
  }
};

}  // namespace detail
}  // namespace top_sim
