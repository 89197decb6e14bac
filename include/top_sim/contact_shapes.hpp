// The body's contact shapes on its figure axis (physics.md section 13): spheres and rims, the point where each meets
// the plane below it, its gap and the kinematics of that point (shape_motion.hpp: a body touching with one).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>


namespace top_sim {

enum class ShapeKind : unsigned char { sphere, rim };
const char* to_string(ShapeKind kind);

// A shape's name as the labels say it ("rolling on tip and crown"): a plain identifier, kept in place so that a
// ShapeSet stays a value without allocation.
constexpr std::size_t kShapeNameSize = 16;  // with the terminating 0
using ShapeName = std::array<char, kShapeNameSize>;

// A sphere (centre r_cm + offset f_hat) or a rim (a circle of that radius, centred there, normal to f_hat).
struct ContactShape {
  ShapeKind kind = ShapeKind::sphere;
  double offset = 0.0;  // d [m]
  double radius = 0.0;  // r of a sphere, rho of a rim [m]
  ShapeName name{};     // empty: unnamed (labels say "shape i")
};

// The body's shapes, at most kMaxShapes (a fixed array: no allocation of its own).
constexpr std::size_t kMaxShapes = 4;
constexpr std::size_t kNoShape = kMaxShapes;  // ShapeSet::second when one shape touches
struct ShapeSet {
  std::array<ContactShape, kMaxShapes> shape{};
  std::size_t count = 0;
  std::size_t touching = 0;  // the shape in contact (set by the Simulator at touchdown; unused in flight); the
                             // state's gap is its own
  std::size_t second = kNoShape;  // a second shape in contact at once (a top on tip and crown), else kNoShape
  std::array<bool, 2> stuck{false, false};  // with a second: contact 0 (touching) and 1 (second) stuck, else slipping
  bool active = false;       // a rim or several shapes: not the tip sphere alone (set with the shapes, shapes_active)
};

inline bool two_touching(const ShapeSet& shapes) { return shapes.second != kNoShape; }

// Shape i's name, or "shape i" when it has none.
inline std::string shape_name(const ShapeSet& shapes, std::size_t i) {
  const char* name = shapes.shape[i].name.data();
  return name[0] != '\0' ? std::string(name) : "shape " + std::to_string(i);
}

// The names of the shapes whose bits are set in `touching`, joined for a label: "tip", "tip and crown".
inline std::string touching_names(const ShapeSet& shapes, std::uint32_t touching) {
  std::string out;
  for (std::size_t i = 0; i < shapes.count; ++i) {
    if ((touching & (1u << i)) == 0) continue;
    touching &= ~(1u << i);
    out += (out.empty() ? "" : (touching == 0 ? " and " : ", ")) + shape_name(shapes, i);
  }
  return out;
}

// Whether `shapes` is more than the tip sphere alone; a ShapeSet built by hand sets `active` with it.
inline bool shapes_active(const ShapeSet& shapes) {
  return shapes.count > 1 || (shapes.count == 1 && shapes.shape[0].kind != ShapeKind::sphere);
}

// Where a shape meets the plane below it (n = e_z), relative to the centre of mass, and how that point moves.
struct ShapePoint {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();       // r_k: the lowest point - r_cm
  Eigen::Vector3d r_rate = Eigen::Vector3d::Zero();  // d r_k / dt: a rim's lowest point runs along the rim
  double height = 0.0;                               // h(c) = n . r_k: the shape's gap is z_cm + h
  double height_slope = 0.0;                         // dh / dc
};

// The tilt's sine s = |n - c f_hat| below which a rim counts as lying flat: its lowest point is then not unique
// (and h'' = rho / s^3 unbounded), the end state of a disc (physics.md section 13).
constexpr double kFlatRimSine = 1e-9;
// The tilt's sine at which a rolling rim's run ends, lying flat (a named end state, not a fault): at 1e-4 a disc of
// 40 mm has its edge 4 um above the plane and circles at Omega = sqrt(4 g / (a s)) = 3.1e3 rad/s.
constexpr double kFlatEndSine = 1e-4;

// A body touching on two shapes is at rest (the end state at_rest, physics.md 13.3) when its centre of mass and its
// shapes' reach move slower than the stick speed and accelerate at less than this fraction of g: the turning point
// of a rocking body is slow but not unaccelerated.
constexpr double kRestAcceleration = 1e-3;

// The farthest any shape reaches from the centre of mass, max |d| + r.
inline double shapes_reach(const ShapeSet& shapes) {
  double reach = 0.0;
  for (std::size_t k = 0; k < shapes.count; ++k)
    reach = std::max(reach, std::abs(shapes.shape[k].offset) + shapes.shape[k].radius);
  return reach;
}

// h(c) with c = n . f_hat: d c - r for a sphere, d c - rho sqrt(1 - c^2) for a rim.
double shape_height(const ContactShape& shape, double c);

// r_k, its rate at angular velocity w, h and h'; f_hat of unit length. A rim needs s > kFlatRimSine.
ShapePoint shape_point(const ContactShape& shape, const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w);

// The shape whose lowest point is lowest (the first of equals).
std::size_t lowest_shape(const ShapeSet& shapes, const Eigen::Vector3d& f_hat);

}  // namespace top_sim
