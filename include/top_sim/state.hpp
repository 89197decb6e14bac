// The integrated state of physics.md section 2, all vectors in the plane frame P.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>

namespace top_sim {

// Layout of the state vector; psi is last so error control can skip it.
namespace idx {
constexpr std::size_t x = 0;       // tip-sphere centre, in-plane (2)
constexpr std::size_t u = 2;       // its in-plane velocity = contact-point velocity (2)
constexpr std::size_t f = 4;       // figure axis f_hat (3)
constexpr std::size_t omega = 7;   // shell angular velocity (3)
constexpr std::size_t nu = 10;     // rotor spin relative to the shell
constexpr std::size_t w_diss = 11; // dissipated work
constexpr std::size_t gap = 12;    // height of the tip-sphere centre above R (flight; exactly 0 in contact)
constexpr std::size_t gap_rate = 13;  // its rate n . u (exactly 0 in contact)
constexpr std::size_t psi = 14;    // spin phase (orientation output only)
constexpr std::size_t size = 15;
}  // namespace idx

using StateVector = std::array<double, idx::size>;

inline Eigen::Vector2d position(const StateVector& y) { return {y[idx::x], y[idx::x + 1]}; }
// Velocity of the tip-sphere centre: in-plane u and the gap rate (0 in contact).
inline Eigen::Vector3d velocity3(const StateVector& y) { return {y[idx::u], y[idx::u + 1], y[idx::gap_rate]}; }
inline Eigen::Vector3d in_plane_velocity(const StateVector& y) { return {y[idx::u], y[idx::u + 1], 0.0}; }
inline Eigen::Vector3d figure_axis(const StateVector& y) { return {y[idx::f], y[idx::f + 1], y[idx::f + 2]}; }
inline Eigen::Vector3d angular_velocity(const StateVector& y) {
  return {y[idx::omega], y[idx::omega + 1], y[idx::omega + 2]};
}

// The shell's spin omega . f_hat [rad/s] (f_hat normalised here: a stepped state drifts off unit length).
inline double shell_spin(const StateVector& y) { return angular_velocity(y).dot(figure_axis(y).normalized()); }

inline void set_position(StateVector& y, const Eigen::Vector2d& p) { y[idx::x] = p.x(); y[idx::x + 1] = p.y(); }
inline void set_velocity(StateVector& y, const Eigen::Vector2d& u) { y[idx::u] = u.x(); y[idx::u + 1] = u.y(); }
inline void set_velocity3(StateVector& y, const Eigen::Vector3d& u) {
  y[idx::u] = u.x(); y[idx::u + 1] = u.y(); y[idx::gap_rate] = u.z();
}
inline void set_figure_axis(StateVector& y, const Eigen::Vector3d& f) {
  y[idx::f] = f.x(); y[idx::f + 1] = f.y(); y[idx::f + 2] = f.z();
}
inline void set_angular_velocity(StateVector& y, const Eigen::Vector3d& w) {
  y[idx::omega] = w.x(); y[idx::omega + 1] = w.y(); y[idx::omega + 2] = w.z();
}

// Renormalise f_hat (physics.md section 2: after each step).
void normalize_figure_axis(StateVector& y);

bool all_finite(const StateVector& y);

}  // namespace top_sim
