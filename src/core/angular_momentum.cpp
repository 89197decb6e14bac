// The top's angular momentum about its centre of mass.
#include "angular_momentum.hpp"

#include <cmath>

namespace top_sim {

Eigen::Vector3d angular_momentum(const Model& model, const StateVector& y) {
  const Top& top = model.top;
  const double J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double nu = top.has_rotor ? y[idx::nu] : 0.0;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized(), w = angular_velocity(y);
  const double w_f = w.dot(f_hat);
  return top.inertia_transverse * (w - w_f * f_hat) + ((top.inertia_axial - J) * w_f + J * (w_f + nu)) * f_hat;
}

double angular_momentum_azimuth(const Model& model, const StateVector& y) {
  const Eigen::Vector3d l = angular_momentum(model, y);
  return l.x() == 0.0 && l.y() == 0.0 ? 0.0 : std::atan2(l.y(), l.x());
}

}  // namespace top_sim
