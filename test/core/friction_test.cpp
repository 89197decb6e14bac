// Friction laws mu(s) of physics.md section 4: values, the clamp at 0, slopes and validation messages.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "test_util.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/stationary.hpp"

namespace {

using namespace top_sim;

FrictionLaw paper(double mu_c, double s_c) {
  FrictionLaw law;
  law.kind = FrictionLawKind::paper;
  law.mu_c = mu_c;
  law.s_c = s_c;
  return law;
}

FrictionLaw table(std::vector<std::pair<double, double>> points) {
  FrictionLaw law;
  law.kind = FrictionLawKind::table;
  law.points = std::move(points);
  return law;
}

// Rounding of a few products of O(1) numbers.
constexpr double kExact = 1e-15;

// The adapters' one rule: a change names a law and some parameters; the others keep their values in force.
TEST(FrictionLaws, ChangedLawKeepsWhatTheChangeDoesNotName) {
  FrictionLaw in_force;
  in_force.kind = FrictionLawKind::table;
  in_force.points = {{0.0, 0.1}, {1.0, 0.3}};
  in_force.s_c = 0.45;
  FrictionChange change;
  change.kind = FrictionLawKind::paper;
  change.given.emplace_back(find_friction_parameter("mu_c"), 0.3);
  const FrictionLaw paper = changed_law(in_force, change);
  EXPECT_EQ(paper.kind, FrictionLawKind::paper);
  EXPECT_EQ(paper.mu_c, 0.3);
  EXPECT_EQ(paper.s_c, 0.45);
  FrictionChange back;
  back.kind = FrictionLawKind::table;
  EXPECT_EQ(changed_law(paper, back).points, in_force.points) << "no points given: the table's stay";
  back.points = std::vector<std::pair<double, double>>{{0.0, 0.2}, {1.0, 0.2}};
  EXPECT_EQ(changed_law(paper, back).points, *back.points);
}

TEST(FrictionLaws, PaperLawValuesByHand) {
  const FrictionLaw law = paper(0.25, 0.6);
  // mu_c s (2 s_c - s) / s_c^2 evaluated by hand: s = 0.3 -> 0.25 * 0.3 * 0.9 / 0.36 = 0.1875.
  EXPECT_NEAR(friction_coefficient(law, 0.3), 0.1875, kExact);
  EXPECT_NEAR(friction_coefficient(law, 0.0), 0.0, kExact);
  // The maximum mu_c sits at s = s_c.
  EXPECT_NEAR(friction_coefficient(law, 0.6), 0.25, kExact);
  // s = 1: 0.25 * 1 * 0.2 / 0.36 = 0.13888... (physics.md: mu(1) = mu_c (2 s_c - 1) / s_c^2).
  EXPECT_NEAR(friction_coefficient(law, 1.0), 0.25 * 0.2 / 0.36, kExact);
  EXPECT_FALSE(clamp_is_active(law));  // s_c >= 0.5: mu(s) >= 0 on all of [0, 1]
  EXPECT_NEAR(max_friction_coefficient(law), 0.25, kExact);
  // alpha_c = atan(mu_c).
  EXPECT_NEAR(critical_inclination(law), std::atan(0.25), kExact);
}

TEST(FrictionLaws, PaperLawIsClampedAtZeroBeyondTwiceSc) {
  const FrictionLaw law = paper(0.25, 0.4);
  // Raw value at s = 0.9: 0.25 * 0.9 * (0.8 - 0.9) / 0.16 = -0.140625 (propelling, hence clamped).
  EXPECT_NEAR(raw_friction_coefficient(law, 0.9), -0.140625, kExact);
  EXPECT_EQ(friction_coefficient(law, 0.9), 0.0);  // exactly 0: friction never propels
  EXPECT_EQ(friction_coefficient(law, 0.8), 0.0);  // the root 2 s_c itself
  EXPECT_TRUE(clamp_is_active(law));
  // Never negative anywhere on [0, 1]; checked on a fine grid that includes the clamped range.
  for (int i = 0; i <= 1000; ++i) EXPECT_GE(friction_coefficient(law, i / 1000.0), 0.0) << "s = " << i / 1000.0;
  // The clamped part has zero slope: no restoring force from a region that has no friction.
  EXPECT_EQ(friction_slope(law, 0.95), 0.0);
}

TEST(FrictionLaws, LinearizedLawValuesAndClamp) {
  FrictionLaw law;
  law.kind = FrictionLawKind::linearized;
  law.mu0 = 0.1;
  law.k = 1.0;
  law.s0 = 0.3;
  // mu0 + k (s - s0): 0.1 + 0.2 = 0.3 at s = 0.5.
  EXPECT_NEAR(friction_coefficient(law, 0.5), 0.3, kExact);
  EXPECT_NEAR(friction_coefficient(law, 0.3), 0.1, kExact);
  // Raw -0.2 at s = 0: clamped to 0.
  EXPECT_NEAR(raw_friction_coefficient(law, 0.0), -0.2, kExact);
  EXPECT_EQ(friction_coefficient(law, 0.0), 0.0);
  EXPECT_EQ(friction_coefficient(law, 0.1), 0.0);
  EXPECT_TRUE(clamp_is_active(law));
  EXPECT_NEAR(friction_slope(law, 0.5), 1.0, kExact);
}

TEST(FrictionLaws, CoulombLawIsConstant) {
  FrictionLaw law;
  law.kind = FrictionLawKind::coulomb;
  law.mu = 0.37;
  for (double s : {0.0, 0.2, 0.5, 1.0}) EXPECT_EQ(friction_coefficient(law, s), 0.37) << "s = " << s;
  EXPECT_EQ(friction_slope(law, 0.5), 0.0);
  EXPECT_FALSE(clamp_is_active(law));
}

TEST(FrictionLaws, TableLawInterpolatesLinearlyAndClamps) {
  const FrictionLaw law = table({{0.0, 0.0}, {0.5, 0.3}, {1.0, 0.2}});
  // Through the points exactly, and linear in between: midpoints by hand.
  EXPECT_NEAR(friction_coefficient(law, 0.0), 0.0, kExact);
  EXPECT_NEAR(friction_coefficient(law, 0.5), 0.3, kExact);
  EXPECT_NEAR(friction_coefficient(law, 1.0), 0.2, kExact);
  EXPECT_NEAR(friction_coefficient(law, 0.25), 0.15, kExact);
  EXPECT_NEAR(friction_coefficient(law, 0.75), 0.25, kExact);
  EXPECT_NEAR(friction_slope(law, 0.25), 0.6, 1e-14);
  EXPECT_NEAR(friction_slope(law, 0.75), -0.2, 1e-14);
  EXPECT_FALSE(clamp_is_active(law));

  const FrictionLaw negative = table({{0.0, 0.1}, {1.0, -0.1}});
  // Raw value at s = 0.75 is -0.05: clamped to 0; at s = 0.25 it is +0.05.
  EXPECT_NEAR(raw_friction_coefficient(negative, 0.75), -0.05, kExact);
  EXPECT_EQ(friction_coefficient(negative, 0.75), 0.0);
  EXPECT_NEAR(friction_coefficient(negative, 0.25), 0.05, kExact);
  EXPECT_TRUE(clamp_is_active(negative));
}

// The analytic slopes used for the stability of the sleeping branch agree with difference quotients of mu(s).
TEST(FrictionLaws, SlopeMatchesDifferenceQuotient) {
  FrictionLaw lin;
  lin.kind = FrictionLawKind::linearized;
  lin.mu0 = 0.2;
  lin.k = -0.5;
  lin.s0 = 0.2;
  for (const FrictionLaw& law : {paper(0.25, 0.6), paper(0.4, 0.35), lin}) {
    for (double s : {0.05, 0.2, 0.45, 0.65}) {
      const double h = 1e-6;
      const double dq = (friction_coefficient(law, s + h) - friction_coefficient(law, s - h)) / (2 * h);
      // Central difference of a quadratic is exact up to rounding ~1e-16 / 1e-6 = 1e-10.
      EXPECT_NEAR(friction_slope(law, s), dq, 1e-8) << to_string(law.kind) << " at s = " << s;
    }
  }
}

// validate() returns "field = value: must be range"; check each piece is named.
void expect_names(const std::string& msg, const std::string& field, const std::string& value,
                  const std::string& range) {
  EXPECT_NE(msg.find(field), std::string::npos) << "field '" << field << "' missing in: " << msg;
  EXPECT_NE(msg.find(value), std::string::npos) << "value '" << value << "' missing in: " << msg;
  EXPECT_NE(msg.find(range), std::string::npos) << "range '" << range << "' missing in: " << msg;
}

TEST(FrictionLaws, ValidationNamesFieldValueAndRange) {
  EXPECT_EQ(validate(paper(0.25, 0.6)), "");
  expect_names(validate(paper(0.0, 0.6)), "mu_c", "0", "> 0");
  expect_names(validate(paper(-0.3, 0.6)), "mu_c", "-0.3", "> 0");
  expect_names(validate(paper(0.25, 1.5)), "s_c", "1.5", "(0, 1]");
  expect_names(validate(paper(0.25, 0.0)), "s_c", "0", "(0, 1]");

  FrictionLaw coulomb;
  coulomb.kind = FrictionLawKind::coulomb;
  coulomb.mu = -0.1;
  expect_names(validate(coulomb), "friction.mu", "-0.1", ">= 0");

  FrictionLaw lin;
  lin.kind = FrictionLawKind::linearized;
  lin.s0 = 1.5;
  expect_names(validate(lin), "s0", "1.5", "[0, 1]");

  // Unsorted table: the second point's s is not above the first.
  expect_names(validate(table({{0.5, 0.2}, {0.2, 0.3}})), "points[1]", "0.2", "greater than the previous");
  // s outside [0, 1].
  expect_names(validate(table({{-0.1, 0.2}, {0.5, 0.3}})), "points[0]", "-0.1", "[0, 1]");
  expect_names(validate(table({{0.0, 0.2}, {1.2, 0.3}})), "points[1]", "1.2", "[0, 1]");
  // Fewer than two points.
  const std::string one = validate(table({{0.5, 0.2}}));
  EXPECT_NE(one.find("points"), std::string::npos) << one;
  EXPECT_NE(one.find("at least 2"), std::string::npos) << one;
}

// The parameter table is what scene parsing, validation and the adapters iterate: each law's keys come from it.
TEST(FrictionLaws, ParameterTableNamesEachLawsKeysAndRanges) {
  EXPECT_EQ(friction_parameter_names(FrictionLawKind::paper), "mu_c, s_c");
  EXPECT_EQ(friction_parameter_names(FrictionLawKind::linearized), "mu0, k, s0");
  EXPECT_EQ(friction_parameter_names(FrictionLawKind::coulomb), "mu");
  EXPECT_EQ(friction_parameter_names(FrictionLawKind::table), "points");
  EXPECT_EQ(friction_law_names(" | "), "paper | linearized | coulomb | table");
  for (const FrictionLawName& n : kFrictionLawNames) {
    FrictionLawKind k;
    ASSERT_TRUE(parse_friction_law_kind(n.name, k));
    EXPECT_EQ(k, n.kind);
    EXPECT_STREQ(to_string(n.kind), n.name);
  }
  for (const FrictionParameter& p : kFrictionParameters) {
    SCOPED_TRACE(p.name);
    EXPECT_EQ(find_friction_parameter(p.name), &p);
    FrictionLaw law;
    law.kind = p.law;
    EXPECT_EQ(validate(law), "");  // the defaults are admissible
    law.*p.member = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(validate(law).rfind(std::string("friction.") + p.name + " = nan: must be " + p.range.text(), 0), 0u)
        << validate(law);
  }
  EXPECT_EQ(find_friction_parameter("points"), nullptr);
  EXPECT_EQ(ParameterRange::above(0.0).text(), "> 0");
  EXPECT_EQ(ParameterRange::at_least(0.0).text(), ">= 0");
  EXPECT_EQ(ParameterRange::between(0.0, true, 1.0, false).text(), "in (0, 1]");
  EXPECT_EQ(ParameterRange::any().text(), "a finite number");
  EXPECT_FALSE(ParameterRange::any().admits(std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(ParameterRange::between(0.0, false, 1.0, false).admits(1.0));
  EXPECT_FALSE(ParameterRange::between(0.0, true, 1.0, false).admits(0.0));
}

}  // namespace
