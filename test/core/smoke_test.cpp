#include <gtest/gtest.h>
#include "top_sim/friction.hpp"
TEST(Smoke, PaperLawPeak) {
  top_sim::FrictionLaw law;
  EXPECT_NEAR(top_sim::friction_coefficient(law, law.s_c), law.mu_c, 1e-15);
}
