// The state's helpers: the finiteness check the simulator runs after every step.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "top_sim/state.hpp"

namespace {

using namespace top_sim;

StateVector finite_state() {
  StateVector y{};
  for (std::size_t i = 0; i < y.size(); ++i)
    y[i] = (i % 2 ? -1.0 : 1.0) * std::pow(10.0, static_cast<double>(i) * 20.0 - 150.0);
  return y;
}

TEST(State, AllFiniteAcceptsFiniteStatesOfAnyMagnitudeAndSign) {
  EXPECT_TRUE(all_finite(finite_state()));  // 1e-150 .. 1e130, both signs
  StateVector y{};
  y[3] = -0.0;
  y[5] = std::numeric_limits<double>::max();
  y[6] = -std::numeric_limits<double>::max();
  y[7] = std::numeric_limits<double>::denorm_min();
  EXPECT_TRUE(all_finite(y));
}

TEST(State, AllFiniteRejectsInfinityOrNaNInEveryComponent) {
  for (double bad : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()})
    for (std::size_t i = 0; i < idx::size; ++i) {
      StateVector y = finite_state();
      y[i] = bad;
      EXPECT_FALSE(all_finite(y)) << "component " << i << " = " << bad;
    }
}

}  // namespace
