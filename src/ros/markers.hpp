// What rviz draws of a top (docs/ros.md, "Watching in rviz"): markers attached to frames that tf moves at the tf
// rate, so nothing drawn on a top lags it whatever marker_rate is; the plane's grid and the trail stay in the plane.
#pragma once

#include <string>

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.hpp"
#include "trail.hpp"
#include "top_sim/model.hpp"
#include "top_sim/snapshot.hpp"

namespace top_sim_ros {

enum class ColorBy { regime, mode };

// "regime" or "mode" -> `out`; false for anything else.
bool parse_color_by(const std::string& text, ColorBy& out);

struct Rgb {
  float r, g, b;
};

// The body's colour: by regime (sleeping green, nutating orange, ...) or by contact mode (slipping grey, ...).
Rgb body_colour(const top_sim::Snapshot& s, ColorBy by);

// The label above a top: "NAME: regime, contact mode, phi 0.270 / phi* 0.270" (phi* when the snapshot has a
// stationary state); a faulted top shows its fault instead.
std::string status_text(const std::string& name, const top_sim::Snapshot& s);

struct MarkerStyle {
  std::string name;                 // the top's name, shown in its label
  ColorBy color_by = ColorBy::regime;
  double grid_pitch = 0.05;         // [m] between grid lines
  int grid_cells = 40;              // lines drawn across the grid's square, centred on the contact point
};

// The top's markers: body, stripe, stem, tip sphere and spin arrow in the top frame; velocity arrow and label in
// the contact frame (plane axes, so the arrow keeps its direction on the plane); the grid in the grid frame.
// One marker per namespace, each with its own fixed small id; every marker frame-locked.
void to_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                const MarkerStyle& style, visualization_msgs::MarkerArray& out);

// The trail (the ~path's poses, in the plane frame) as a LINE_STRIP in namespace "trail".
visualization_msgs::Marker trail_marker(const Trail& path, const ros::Time& stamp, const std::string& plane_frame);

}  // namespace top_sim_ros
