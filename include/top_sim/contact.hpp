// Kinematics at the contact and contact faults (physics.md sections 3, 4 and 9).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "top_sim/model.hpp"

namespace top_sim {

// Velocities at the contact point and the slip parameter (physics.md section 3).
struct ContactKinematics {
  Eigen::Vector3d v_t = Eigen::Vector3d::Zero();    // material velocity of the top at the contact (in-plane)
  Eigen::Vector3d t_hat = Eigen::Vector3d::Zero();  // regularised friction direction
  double rolling_speed = 0.0;                       // R |omega x n|
  double slip = 0.0;                                // s in [0, 1]
};

// The material velocity of the top at the contact point, u - R omega x n (n = e_z); inline: every right-hand side
// starts here.
inline Eigen::Vector3d contact_velocity(const Model& model, const Eigen::Vector3d& u, const Eigen::Vector3d& omega) {
  return u - model.top.tip_radius * Eigen::Vector3d(omega.y(), -omega.x(), 0.0);
}

// v_t and the rolling speed only: on a patch the slip and the friction direction come from the law (section 12).
inline ContactKinematics contact_velocities(const Model& model, const Eigen::Vector3d& u, const Eigen::Vector3d& omega) {
  ContactKinematics k;
  k.v_t = contact_velocity(model, u, omega);
  k.rolling_speed = model.top.tip_radius * Eigen::Vector3d(omega.y(), -omega.x(), 0.0).norm();  // R |omega x n|
  return k;
}

// |v| and sqrt(|v|^2 + e^2) without the squares' spurious overflow beyond 1e154: a tip sphere of 1e300 m turning at
// 1e-3 rad/s has a finite v_t whose norm() was inf, and so was the slip (fuzz finding 8). Below it, the plain formulas
// to the bit.
inline double safe_norm(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return std::isfinite(n) || !v.allFinite() ? n : std::hypot(v.x(), v.y(), v.z());
}
inline double regularized_norm(double n, double e) {
  const double s = n * n + e * e;
  return std::isfinite(s) ? std::sqrt(s) : std::hypot(n, e);
}

inline ContactKinematics contact_kinematics(const Model& model, const Eigen::Vector3d& u, const Eigen::Vector3d& omega) {
  ContactKinematics k;
  const double R = model.top.tip_radius;
  const double v_eps = model.regularization_speed;
  const Eigen::Vector3d omega_x_n(omega.y(), -omega.x(), 0.0);  // omega x n with n = e_z
  k.v_t = contact_velocity(model, u, omega);
  k.rolling_speed = R * omega_x_n.norm();
  const double vt = safe_norm(k.v_t);
  k.slip = vt / (u.norm() + k.rolling_speed + v_eps);
  k.t_hat = k.v_t / regularized_norm(vt, v_eps);
  return k;
}

// Faults stop the top where the model cannot go on (physics.md sections 4, 8 and 9); lift-off is not a fault but a
// switch to flight, and a body that falls has reached an end (EndState::fallen), not a fault.
enum class ContactFault { none, painleve, numerical };

const char* to_string(ContactFault fault);

// Ends of a run that are no fault (physics.md sections 8 and 13): the run stops there and says so. `fallen`: the
// figure axis passed max_tilt with no shape to catch the body.
enum class EndState { none, lying_flat, at_rest, fallen };
constexpr int kEndStateCount = 4;  // adapters read a recorded name back over these codes

const char* to_string(EndState state);
std::string describe(EndState state, double margin, double t);

// One line for the user: what happened at time t and the number that shows it (the margin of the fault).
std::string describe(ContactFault fault, double value, double t);

}  // namespace top_sim
