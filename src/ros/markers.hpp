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
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
};

// The body's colour: by regime (sleeping green, nutating orange, ...) or by contact mode (slipping grey, ...).
Rgb body_colour(const top_sim::Snapshot& s, ColorBy by);

// WCAG 2 contrast ratio of two sRGB colours, from 1 (same luminance) to 21 (black on white).
double contrast_ratio(Rgb a, Rgb b);
// What a label is read against: rviz's background (rviz/top_sim.rviz) and the translucent plane square over it.
Rgb rviz_background();
Rgb plane_over_background();
// `c` mixed with white just enough to reach `ratio` against both backgrounds above (label text: 4.5, WCAG AA).
Rgb readable(Rgb c, double ratio = 4.5);

// A top's state in words: "NAME: regime, contact mode" and "phi 0.270 / phi* 0.270, v 1.2 mm/s" (phi* when the
// snapshot has a stationary state, v the contact point's speed on the plane), joined by `line_break` (the label
// above a top: "\n"); with the body's `shapes` the regime names what touches ("rolling on tip and crown"). A
// faulted top shows its fault instead, a top at its end only that end and its time ("end: lying_flat at t = 63.10 s").
std::string status_text(const std::string& name, const top_sim::Snapshot& s, const std::string& line_break = ", ",
                        const top_sim::ShapeSet* shapes = nullptr);

// The contact point's speed along the plane [m/s]: the centre of mass's velocity without its normal part.
double speed_on_plane(const top_sim::Snapshot& s);

// The grid's pitch for a contact point moving at `speed`: `base` times a power of ten, coarse enough that its lines
// move at most a third of a pitch per frame drawn at 30 Hz (finer lines alias: they seem to stand or run back);
// `current` is kept until the next finer pitch is comfortably enough (no flicker between two pitches).
double grid_pitch_for(double speed, double base, double current);

struct MarkerStyle {
  std::string name;                 // the top's name, shown in its label
  ColorBy color_by = ColorBy::regime;
  double grid_pitch = 0.05;         // [m] between grid lines
  double grid_line_pitch = 0.05;    // [m] the pitch that sets the lines' width (grid_pitch of a top at rest)
  int grid_cells = 40;              // lines drawn across the grid's square, centred on the contact point
};

// The markers that change only with the top's colour, shape or grid pitch: plane, grid, body, stripe, stem and tip
// sphere. One marker per namespace, each with its own fixed small id; every marker frame-locked.
void fixed_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                   const MarkerStyle& style, visualization_msgs::MarkerArray& out);
// The markers that change every tick: the spin arrow in the top frame; the velocity arrow and the label in the
// contact frame (plane axes, so the arrow keeps its direction on the plane).
void moving_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                    const MarkerStyle& style, visualization_msgs::MarkerArray& out);
// Both, after clearing `out`.
void to_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const ros::Time& stamp, const Frames& frames,
                const MarkerStyle& style, visualization_msgs::MarkerArray& out);

// The same for a body that may have contact shapes (model.shapes, physics.md section 13): with `shapes.active` the
// body is drawn from its shapes (top_mesh.hpp, shape_mesh), the touching one(s) in white in namespace "touching" after
// Snapshot::touching, and no tip sphere or stem; without, exactly the markers above.
void fixed_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes,
                   const ros::Time& stamp, const Frames& frames, const MarkerStyle& style,
                   visualization_msgs::MarkerArray& out);
void moving_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes,
                    const ros::Time& stamp, const Frames& frames, const MarkerStyle& style,
                    visualization_msgs::MarkerArray& out);
void to_markers(const top_sim::Snapshot& s, const top_sim::Top& top, const top_sim::ShapeSet& shapes,
                const ros::Time& stamp, const Frames& frames, const MarkerStyle& style,
                visualization_msgs::MarkerArray& out);

// A closed chunk of the trail as a LINE_STRIP in namespace "trail" with the chunk's id, in the plane frame.
visualization_msgs::Marker trail_chunk_marker(const Trail::Chunk& chunk, const ros::Time& stamp,
                                              const std::string& plane_frame);
// The trail's open chunk in namespace "trail_head", up to `contact`, the contact point at `stamp`: in the plane frame,
// or `attached` in the contact frame (its points relative to `contact`), so that it stays behind a fast top between
// marker ticks while the camera follows (its start then leaves the closed chunks' end by the distance moved since).
visualization_msgs::Marker trail_head_marker(const Trail& trail, const Eigen::Vector3d& contact,
                                             const ros::Time& stamp, const Frames& frames, bool attached);

}  // namespace top_sim_ros
