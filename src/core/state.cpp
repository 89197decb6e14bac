#include "top_sim/state.hpp"

#include <cmath>

namespace top_sim {

void normalize_figure_axis(StateVector& y) {
  const double n = std::sqrt(y[idx::f] * y[idx::f] + y[idx::f + 1] * y[idx::f + 1] + y[idx::f + 2] * y[idx::f + 2]);
  if (n > 0.0 && std::isfinite(n))
    for (std::size_t i = 0; i < 3; ++i) y[idx::f + i] /= n;
}

bool all_finite(const StateVector& y) {
  // v * 0 is 0 for a finite v and NaN otherwise: one branch-free sum instead of a test per component.
  double sum = 0.0;
  for (double v : y) sum += v * 0.0;
  return sum == 0.0;
}

}  // namespace top_sim
