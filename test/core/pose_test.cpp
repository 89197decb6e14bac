// The light pose read (top_sim/pose.hpp): the placement of physics.md section 2 against its geometry, and the
// same numbers as the full Snapshot of the state.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_util.hpp"
#include "top_sim/pose.hpp"

namespace {

using namespace top_sim;

Model aluminium_model(double alpha) {
  return top_sim_test::scene_from(top_sim_test::standard_scene(alpha, 200.0)).model;
}

StateVector state_at(double x, double y, const Eigen::Vector3d& f, double psi, double gap) {
  StateVector s{};
  set_position(s, {x, y});
  set_figure_axis(s, f);
  s[idx::psi] = psi;
  s[idx::gap] = gap;
  return s;
}

// Upright: the centre of mass straight above the tip centre (R + l over the plane), the body turned by psi about z.
TEST(Pose, UprightTopIsItsTipCentrePlusTheComOffsetAlongZ) {
  const Model m = aluminium_model(0.1);
  const double R = m.top.tip_radius, l = m.top.com_offset, psi = 0.7;
  const TopPose p = top_pose(m, state_at(0.3, -0.2, Eigen::Vector3d::UnitZ(), psi, 0.0), 4.5);
  EXPECT_EQ(p.t, 4.5);
  EXPECT_EQ(p.alpha, 0.1);
  EXPECT_NEAR((p.contact_point - Eigen::Vector3d(0.3, -0.2, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.tip_center - Eigen::Vector3d(0.3, -0.2, R)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.com - Eigen::Vector3d(0.3, -0.2, R + l)).norm(), 0.0, 1e-15);
  const Eigen::Quaterniond about_z(Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(p.orientation.angularDistance(about_z), 0.0, 1e-12);
}

// Tilted by theta in the x-z plane, in flight at gap g: the body z axis is the (normalised) figure axis and the
// centre of mass is l along it from the tip centre, which is R + g over the contact point.
TEST(Pose, TiltedAxisInFlightPlacesTheComAlongTheNormalisedFigureAxis) {
  const Model m = aluminium_model(0.2);
  const double R = m.top.tip_radius, l = m.top.com_offset, theta = 0.4, g = 2e-3;
  const Eigen::Vector3d f(std::sin(theta), 0.0, std::cos(theta));
  const TopPose p = top_pose(m, state_at(0.0, 0.0, 1.001 * f, 0.0, g), 0.0);  // f_hat drifted 0.1 % off unit
  EXPECT_NEAR((p.tip_center - Eigen::Vector3d(0.0, 0.0, R + g)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.com - Eigen::Vector3d(l * std::sin(theta), 0.0, R + g + l * std::cos(theta))).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.orientation * Eigen::Vector3d::UnitZ() - f).norm(), 0.0, 1e-12);
  EXPECT_NEAR(p.orientation.norm(), 1.0, 1e-12);
  EXPECT_NEAR((p.contact_point - Eigen::Vector3d::Zero()).norm(), 0.0, 1e-15);
}

// p holds the placing fields of s, bit for bit.
void expect_places_as(const TopPose& p, const Snapshot& s) {
  EXPECT_EQ(p.t, s.t);
  EXPECT_EQ(p.alpha, s.alpha);
  EXPECT_EQ(p.tip_center, s.tip_center);
  EXPECT_EQ(p.com, s.com);
  EXPECT_EQ(p.orientation.coeffs(), s.orientation.coeffs());
  EXPECT_EQ(p.contact_point, s.contact_point);
}

// pose() is the snapshot's placing fields, bit for bit, without building a sample.
TEST(Pose, SimulatorPoseEqualsTheSnapshotFields) {
  Simulator sim(top_sim_test::scene_from(top_sim_test::standard_scene(0.1, 200.0)));
  sim.advance_to(0.37);
  const TopPose p = sim.pose();
  expect_places_as(p, sim.snapshot());
  EXPECT_GT(p.contact_point.norm(), 0.0);  // the top has moved: the comparison is not of two defaults
}

// The pose of a snapshot is its placing fields (the node reads it so when it takes the snapshot anyway).
TEST(Pose, PoseOfASnapshotEqualsTheSimulatorPose) {
  Simulator sim(top_sim_test::scene_from(top_sim_test::standard_scene(0.1, 200.0)));
  for (double t : {0.0, 0.21, 1.3}) {
    sim.advance_to(t);
    const Snapshot s = sim.snapshot();
    expect_places_as(top_pose(s), s);
  }
}

TEST(Pose, AllFiniteRejectsANonFiniteField) {
  const double bad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(all_finite(TopPose()));
  TopPose p;
  p.com.y() = bad;
  EXPECT_FALSE(all_finite(p));
  p = TopPose();
  p.orientation.w() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(all_finite(p));
  p = TopPose();
  p.t = bad;
  EXPECT_FALSE(all_finite(p));
  p = TopPose();
  p.contact_point.x() = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(all_finite(p));
}

}  // namespace
