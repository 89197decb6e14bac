// The inclined plane and its frame P (physics.md section 1): x = h (horizontal in the plane), y uphill, z = n.
// Everything that turns a vector between P and the world frame W, and the direction of travel in the plane, is
// defined here once.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace top_sim {

// Plane frame P -> world frame W: the rotation by alpha about x, which lifts the plane's y axis (uphill).
inline Eigen::Quaterniond plane_rotation(double alpha) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
}

// v_W = R(alpha) v_P with R = plane_rotation(alpha), written out so that every caller gets the same bits.
inline Eigen::Vector3d plane_to_world(double alpha, const Eigen::Vector3d& v) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  return Eigen::Vector3d(v.x(), ca * v.y() - sa * v.z(), sa * v.y() + ca * v.z());
}

// v_P = R(alpha)^T v_W.
inline Eigen::Vector3d world_to_plane(double alpha, const Eigen::Vector3d& v) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  return Eigen::Vector3d(v.x(), ca * v.y() + sa * v.z(), -sa * v.y() + ca * v.z());
}

// Gravity (0, 0, -g) of W in the plane frame: world_to_plane(alpha, (0, 0, -g)) without the zero terms, whose
// sum would turn the -0 of alpha = 0 into +0.
inline Eigen::Vector3d gravity_in_plane(double inclination, double gravity) {
  return Eigen::Vector3d(0.0, -gravity * std::sin(inclination), -gravity * std::cos(inclination));
}

// The inclined plane; gravity in the plane frame is cached because every right-hand side needs it.
struct Plane {
  double inclination = 0.1;  // alpha [rad]
  double gravity = 9.81;     // g [m/s^2]
  Eigen::Vector3d g_plane = gravity_in_plane(0.1, 9.81);
};

inline Plane make_plane(double inclination, double gravity) {
  Plane p;
  p.inclination = inclination;
  p.gravity = gravity;
  p.g_plane = gravity_in_plane(inclination, gravity);
  return p;
}

// Direction of travel phi of an in-plane velocity or displacement (dx, dy), plane frame: the angle from h towards
// downhill (-y), in [-pi, pi]. 0 when there is no motion; never -0 (outputs print "0", not "-0").
inline double travel_angle(double dx, double dy) {
  if (dx == 0.0 && dy == 0.0) return 0.0;
  return std::atan2(-dy, dx) + 0.0;
}

}  // namespace top_sim
