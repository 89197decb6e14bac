// Where a top is: the few Snapshot fields that place it (tf, the trail), read without the sample's analysis.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "top_sim/model.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// Plane frame P; each field equals the Snapshot field of the same name (make_snapshot takes them from here).
struct TopPose {
  double t = 0.0;      // simulated time [s]
  double alpha = 0.0;  // inclination [rad]
  Eigen::Vector3d tip_center = Eigen::Vector3d::Zero();
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body axes, z = figure axis
  Eigen::Vector3d contact_point = Eigen::Vector3d::Zero();
};

// The pose of state y of `model` at time t: geometry only (no dynamics, stationary solve or energy).
TopPose top_pose(const Model& model, const StateVector& y, double t);
// The placing fields of a snapshot already taken (a reader of both needs no second pose computation).
TopPose top_pose(const Snapshot& s);

bool all_finite(const TopPose& p);

}  // namespace top_sim
