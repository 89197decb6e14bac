// The fast top's nutation frequency.
#include "nutation.hpp"

#include <cmath>

#include "angular_momentum.hpp"

namespace top_sim {

double fast_top_nutation_frequency(const Model& model, const StateVector& y) {
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const double axial = std::abs(angular_momentum(model, y).dot(f_hat));
  const double sin2 = f_hat.head<2>().squaredNorm();  // sin^2 of the tilt from the normal
  const double lift = top.mass * top.com_offset * top.com_offset * sin2;
  return axial / std::sqrt(top.inertia_transverse * (top.inertia_transverse + lift));
}

}  // namespace top_sim
