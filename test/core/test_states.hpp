// States the core tests build by hand.
#pragma once

#include "top_sim/state.hpp"

namespace top_sim_test {

// A top standing upright at the origin, spinning at w about n, its tip sphere in contact and at rest.
inline top_sim::StateVector upright_state(double w) {
  top_sim::StateVector y{};
  y[top_sim::idx::f + 2] = 1.0;
  y[top_sim::idx::omega + 2] = w;
  return y;
}

}  // namespace top_sim_test
