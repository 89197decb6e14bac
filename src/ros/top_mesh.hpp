// The drawn top: a body of revolution sized from top_sim::Top, as triangles for an rviz TRIANGLE_LIST marker.
// Pure geometry in the top frame (origin at the centre of mass, z = figure axis); no ROS types, no physics.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "top_sim/model.hpp"

namespace top_sim_ros {

// Sizes of the drawn top [m]. The model has no outer shape: the body is the uniform disc with the top's axial
// inertia (I_f = m r^2 / 2), its rim centred on the centre of mass, a cone down to the tip sphere (f below).
struct TopShape {
  double body_radius = 0.0;   // r_b = sqrt(2 I_f / m)
  double rim_height = 0.0;    // t = max(r_b / 4, 2 R): a disc that still reads as one beside the tip sphere
  double stem_radius = 0.0;   // r_s = max(0.12 r_b, 0.75 R), at most r_b / 2
  double stem_bottom = 0.0;   // z where the stem leaves the body (the top of the cap, = t)
  double stem_top = 0.0;      // t + max(f, r_b / 2)
  // (r, z) from the axis at the tip-sphere centre (z = -f) round the outside to the axis under the stem:
  // counter-clockwise in the (r, z) half-plane, so revolve() turns it into outward-facing triangles.
  std::vector<Eigen::Vector2d> profile;
  // A ball-shaped top's stem: the cap of its sphere from the stem's foot to the pole, drawn in another colour (the
  // physics models only the sphere, so nothing is drawn outside it); empty for an ordinary top (a cylinder).
  std::vector<Eigen::Vector2d> cap;
};

// An ordinary top (f >= 0) as above; a tippe top (f < 0, the centre of mass below the sphere's centre) as its sphere
// with the stem's place painted round the pole along +f_hat (body_radius = R).
TopShape top_shape(const top_sim::Top& top);

// Triangles (three points each, counter-clockwise seen from outside) of `profile` turned about z through `sweep`
// radians from angle `start` in `segments` steps. A full turn (sweep >= 2 pi) closes exactly at the seam; points
// of the profile on the axis (r = 0) give fans without degenerate triangles.
std::vector<Eigen::Vector3d> revolve(const std::vector<Eigen::Vector2d>& profile, int segments, double start,
                                     double sweep);

// The profile's points off the axis, pushed out by `distance` along the profile's outward vertex normals:
// a band turned from it lies just above the body's surface (a painted stripe without depth fighting).
std::vector<Eigen::Vector2d> raised_profile(const std::vector<Eigen::Vector2d>& profile, double distance);

// ---- A body with contact shapes (top.shapes, physics.md section 13): drawn from its shapes alone, nothing outside
// their convex hull (so nothing drawn dips below the plane while the shapes stay above it).

// The drawn thickness of the rims [m]: a lone rim (a disc) as the uniform cylinder of the body's inertias,
// I_d = m (rho^2 / 4 + t^2 / 12), where that gives t > 0; else (a thin disc, a crown) kThinRim rho.
constexpr double kThinRim = 0.05;
// A rim's tyre: its edge band and the outer kTyre of its radius on both faces, one piece (highlighted when touching:
// a disc's edge alone is a few pixels wide at rviz's usual distances).
constexpr double kTyre = 0.12;
double rim_thickness(const top_sim::Top& top, const top_sim::ShapeSet& shapes, std::size_t i);

// Triangles in the top frame (z = figure axis, origin at the centre of mass), counter-clockwise from outside.
struct ShapeMesh {
  std::vector<Eigen::Vector3d> body;      // the shapes not touching, the rims' faces, the joins between shapes
  std::vector<Eigen::Vector3d> touching;  // the touching shapes: a sphere whole, a rim its tyre (below)
  std::vector<Eigen::Vector3d> stripe;    // a band on the widest shape, painted: the spin shows as its turning
};

// [m] no drawn point of the shapes is farther than this from the centre of mass (a rim's thickness either side).
double shape_reach(const top_sim::Top& top, const top_sim::ShapeSet& shapes);

// [m] how far the drawn body reaches from its contact point, at any tilt: the diameter of the shapes' reach about
// the centre of mass; an ordinary top's body radius plus its centre of mass's height (where the body is widest).
double reach_from_contact(const top_sim::Top& top, const top_sim::ShapeSet& shapes);

// Each sphere as a sphere at its centre, each rim as a disc of its radius normal to z, consecutive shapes along z
// joined by the truncated cone between their widest circles. A lone rim's thickness goes from its circle towards
// +z when `rim_up`, else -z: the side away from the plane, so its circle stays the lowest drawn edge, lying flat
// included; with other shapes, a rim's goes up, the lowest shape's down (away from the rest). `touching`: bit i
// for shape i.
ShapeMesh shape_mesh(const top_sim::Top& top, const top_sim::ShapeSet& shapes, std::uint32_t touching, bool rim_up,
                     int segments, double stripe_width, double stripe_raise);

}  // namespace top_sim_ros
