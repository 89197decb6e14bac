// Snapshot -> ROS messages, TopState -> Snapshot and TopCommand -> core Command: field-by-field maps, no physics.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <string>

#include "top_sim/TopCommand.h"
#include "top_sim/TopState.h"
#include "top_sim/command.hpp"
#include "top_sim/model.hpp"
#include "top_sim/pose.hpp"
#include "top_sim/snapshot.hpp"

namespace top_sim_ros {

struct Frames {
  std::string world = "world";
  std::string plane = "plane";
  std::string top = "top";
  std::string contact = "contact";  // origin at the contact point, plane axes (markers that keep their direction)
  std::string grid = "grid";        // the contact point snapped to the grid pitch, plane axes (the grid's centre)
};

geometry_msgs::Point point(const Eigen::Vector3d& v);
geometry_msgs::Vector3 vector(const Eigen::Vector3d& v);
geometry_msgs::Quaternion quaternion(const Eigen::Quaterniond& q);

void to_msg(const top_sim::Snapshot& s, const ros::Time& stamp, const std::string& plane_frame,
            top_sim::TopState& out);

// The inverse of to_msg (a recorded state back to the core's Snapshot, e.g. for top_sim_run's CSV). TopState
// carries no spin_phase, com_acceleration, regime indicators or fault kind: those keep their defaults (fault stays
// none; fault_message holds the text); the end state comes back from its name. "" or an error naming field, value
// and allowed range in `error` (a code out of range, an unknown end state, a non-finite number).
top_sim::Snapshot to_snapshot(const top_sim::TopState& msg, std::string& error);

// The frames read the top's pose alone (Simulator::pose(): no sample analysed for tf).
// world -> plane (rotation alpha about x) and plane -> top (centre of mass, body axes).
void to_transforms(const top_sim::TopPose& s, const ros::Time& stamp, const Frames& frames,
                   geometry_msgs::TransformStamped& world_plane, geometry_msgs::TransformStamped& plane_top);

// plane -> contact: the contact point with the plane's axes.
void to_contact_transform(const top_sim::TopPose& s, const ros::Time& stamp, const Frames& frames,
                          geometry_msgs::TransformStamped& plane_contact);

// plane -> grid: the contact point snapped to multiples of `pitch` in the plane, plane axes; lines drawn about
// its origin at multiples of the pitch keep their place on the plane while the grid follows the top.
void to_grid_transform(const top_sim::TopPose& s, double pitch, const ros::Time& stamp, const Frames& frames,
                       geometry_msgs::TransformStamped& plane_grid);

// The set fields of a TopCommand (the core's; reset and pause are the node's, NodeTop::command); "" or an error
// naming field, value and allowed range in `error` (also when no field, reset or set_paused is set). A friction
// change names the law and the parameters the message gives (friction_given, else the law's nonzero fields); the
// core applies it over the law in force (top_sim::changed_law, the rule of every adapter).
top_sim::Command command_from_message(const top_sim::TopCommand& msg, std::string& error);

}  // namespace top_sim_ros
