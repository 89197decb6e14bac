#include "top_sim/pose.hpp"

#include <cmath>

#include "shape_motion.hpp"
#include "orientation.hpp"

namespace top_sim {

TopPose top_pose(const Model& model, const StateVector& y, double t) {
  TopPose p;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  p.t = t;
  p.alpha = model.plane.inclination;
  p.tip_center = Eigen::Vector3d(y[idx::x], y[idx::x + 1], model.top.tip_radius + y[idx::gap]);
  p.com = p.tip_center + model.top.com_offset * f_hat;
  p.orientation = body_orientation(f_hat, y[idx::psi]);
  p.contact_point = Eigen::Vector3d(y[idx::x], y[idx::x + 1], 0.0);
  if (has_shapes(model)) {  // the state's gap is the touching shape's; the contact point below its lowest point
    p.com = shape_body_com(model, y);
    p.tip_center = p.com - model.top.com_offset * f_hat;
    const ContactShape& shape = model.shapes.shape[model.shapes.touching];
    p.contact_point = p.com + shape_point(shape, f_hat, Eigen::Vector3d::Zero()).r;
    p.contact_point.z() = 0.0;
  }
  return p;
}

TopPose top_pose(const Snapshot& s) {
  return TopPose{s.t, s.alpha, s.tip_center, s.com, s.orientation, s.contact_point};
}

bool all_finite(const TopPose& p) {
  return std::isfinite(p.t) && std::isfinite(p.alpha) && p.tip_center.allFinite() && p.com.allFinite() &&
         p.orientation.coeffs().allFinite() && p.contact_point.allFinite();
}

}  // namespace top_sim
