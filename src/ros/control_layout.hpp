// Where top_sim_interactive's controls rest in a top's contact frame (docs/ros.md, "Control in rviz"): beside the
// top, small, not over its body. The label above a top is placed clear of them (markers.cpp).
#pragma once

namespace top_sim_ros::control_layout {

constexpr double kOffsetX = 0.05;  // [m] beside the top along the plane's x axis
constexpr double kHeight = 0.03;   // [m] above the contact point
constexpr double kScale = 0.04;    // [m] the interactive marker's scale: its ring and arrows reach about this far
constexpr double kTop = kHeight + kScale;  // [m] the highest point of the controls above the contact point

// [m] where the controls rest beside a body that reaches `reach` from its contact point (top_mesh.hpp's
// reach_from_contact, the node's ~view/reach): clear of it by half the ring, at least kOffsetX.
inline double offset_x(double reach) { return reach + 0.5 * kScale > kOffsetX ? reach + 0.5 * kScale : kOffsetX; }

}  // namespace top_sim_ros::control_layout
