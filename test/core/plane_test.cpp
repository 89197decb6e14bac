// The plane frame's one definition (include/top_sim/plane.hpp): the written-out rotations agree with the
// quaternion, gravity is (0, 0, -g) of the world, and the travel angle's conventions.
#include <gtest/gtest.h>

#include <cmath>

#include "top_sim/plane.hpp"

namespace {

using namespace top_sim;

TEST(Plane, RotationsAgreeWithTheQuaternion) {
  const Eigen::Vector3d v(0.3, -1.2, 2.5);
  for (double alpha : {-1.2, -0.1, 0.0, 0.1, 0.7}) {
    const Eigen::Quaterniond q = plane_rotation(alpha);
    EXPECT_LT((plane_to_world(alpha, v) - q * v).norm(), 1e-15 * v.norm());
    EXPECT_LT((world_to_plane(alpha, v) - q.conjugate() * v).norm(), 1e-15 * v.norm());
    EXPECT_LT((world_to_plane(alpha, plane_to_world(alpha, v)) - v).norm(), 1e-15 * v.norm());
  }
}

TEST(Plane, UphillIsLiftedAndGravityIsVertical) {
  const double alpha = 0.3, g = 9.81;
  const Eigen::Vector3d up = plane_to_world(alpha, Eigen::Vector3d::UnitY());  // plane y seen from the world
  EXPECT_NEAR(up.y(), std::cos(alpha), 1e-15);
  EXPECT_NEAR(up.z(), std::sin(alpha), 1e-15);
  const Plane p = make_plane(alpha, g);
  EXPECT_EQ(p.g_plane, gravity_in_plane(alpha, g));
  EXPECT_LT((p.g_plane - world_to_plane(alpha, Eigen::Vector3d(0.0, 0.0, -g))).norm(), 1e-15 * g);
  EXPECT_LT((plane_to_world(alpha, p.g_plane) - Eigen::Vector3d(0.0, 0.0, -g)).norm(), 1e-15 * g);
  EXPECT_EQ(Plane().g_plane, make_plane(Plane().inclination, Plane().gravity).g_plane);
}

TEST(Plane, TravelAngleConventions) {
  EXPECT_EQ(travel_angle(1.0, 0.0), 0.0);
  EXPECT_FALSE(std::signbit(travel_angle(1.0, 0.0)));   // atan2(-0, 1) would be -0
  EXPECT_FALSE(std::signbit(travel_angle(1.0, -0.0)));
  EXPECT_EQ(travel_angle(0.0, 0.0), 0.0);               // no motion
  EXPECT_FALSE(std::signbit(travel_angle(-0.0, -0.0)));
  EXPECT_NEAR(travel_angle(0.0, -1.0), M_PI / 2, 1e-15);  // straight downhill
  EXPECT_NEAR(travel_angle(0.0, 1.0), -M_PI / 2, 1e-15);  // straight uphill
  EXPECT_NEAR(travel_angle(-1.0, -1e-300), M_PI, 1e-15);
}

}  // namespace
