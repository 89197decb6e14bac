// The top_sim scene as a MuJoCo model: a free body with the top's mass and explicit inertia, its tip a sphere geom,
// the inclined plane a plane geom, frictionless contact (condim 1), RK4 with solref (2 dt, 1).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "top_sim/scene.hpp"

struct mjModel_;
struct mjData_;

namespace peer {

// An MJCF text compiled through MuJoCo's in-memory file system (throws with MuJoCo's message).
mjModel_* compile(const std::string& xml);

// A number as MJCF text, all 17 digits (the model is the one the code describes, to the bit).
std::string num(double v);
// This thread's CPU time [s] (the benches run one thread: other agents' load does not count).
double thread_cpu();
double median(std::vector<double> v);

// The MJCF of `scene`'s top and plane (angles in radians: <compiler angle="radian"/>).
std::string mjcf(const top_sim::Scene& scene, double dt);

// The body's state in MuJoCo's coordinates (free joint), mapped from top_sim's initial state.
struct FreeBodyState {
  Eigen::Vector3d com = Eigen::Vector3d::Zero();          // world [m]
  Eigen::Vector4d quat = Eigen::Vector4d(1, 0, 0, 0);     // w, x, y, z: body z = figure axis
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero(); // world [m/s]
  Eigen::Vector3d omega_body = Eigen::Vector3d::Zero();   // body frame [rad/s] (MuJoCo's free-joint convention)
};
FreeBodyState initial_free_body(const top_sim::Scene& scene);

// What MuJoCo itself reports for the initial state (mj_forward), for the mapping check.
struct InitialReport {
  Eigen::Vector3d tip_center_plane, figure_axis_world, com_velocity_world, omega_world;
};

class MujocoTop {
 public:
  explicit MujocoTop(const top_sim::Scene& scene);
  ~MujocoTop();
  MujocoTop(const MujocoTop&) = delete;
  MujocoTop& operator=(const MujocoTop&) = delete;

  // RK4 step dt and the stiffest contact MuJoCo allows at it: solref time constant 2 dt, damping ratio 1
  // (a larger time constant: a softer contact, for the study of where MuJoCo's error comes from).
  void set_timestep(double dt, double time_constant = 0.0);
  // Runs from the initial state to T; the in-plane contact point every `interval` (a multiple of dt), from t = 0.
  std::vector<Eigen::Vector2d> run(double T, double interval);
  // Runs from the initial state to T; the figure axis's angle from the plane normal after every step at t >= from
  // [rad] (untimed: the nutation measurement of bench/peer_mujoco).
  std::vector<double> tilt_run(double T, double from);
  InitialReport initial_report();
  // Deepest penetration of the tip into the plane at the samples of the last run() [m].
  double max_penetration() const { return max_penetration_; }

 private:
  void reset();
  Eigen::Vector3d tip_center_plane() const;
  double tilt() const;

  top_sim::Scene scene_;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  int steps_per_sample_ = 1;
  double max_penetration_ = 0.0;
};

}  // namespace peer
