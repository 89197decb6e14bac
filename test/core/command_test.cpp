// Validation of run-time commands (command.hpp): each refusal names the field, the value and the allowed range.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>
#include <string>

#include "test_util.hpp"
#include "top_sim/command.hpp"
#include "top_sim/command_fields.hpp"
#include "top_sim/format.hpp"
#include "top_sim/limits.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

using namespace top_sim;

namespace {

Model model_of(const std::string& scene) { return load_scene(top_sim_test::scene_path(scene)).model; }

::testing::AssertionResult refused(const Command& c, const Model& m, const std::string& field,
                                   const std::string& range_part) {
  const std::string e = validate(c, m);
  if (e.empty()) return ::testing::AssertionFailure() << field << ": accepted";
  if (e.find(field) == std::string::npos || e.find(range_part) == std::string::npos)
    return ::testing::AssertionFailure() << "message '" << e << "' lacks '" << field << "' or '" << range_part << "'";
  return ::testing::AssertionSuccess();
}

}  // namespace

TEST(Command, AnEmptyCommandIsValidForEveryKindOfModel) {
  for (const char* scene : {"default", "coulomb", "gyro_reversal", "tippe_top", "spin_down"})
    EXPECT_EQ(validate(Command{}, model_of(scene)), "") << scene;
}

TEST(Command, InclinationMustBeFiniteAndBelowAQuarterTurn) {
  const Model m = model_of("default");
  Command c;
  c.inclination = 0.3;
  EXPECT_EQ(validate(c, m), "");
  for (double bad : {M_PI / 2, -M_PI / 2, double(NAN), double(INFINITY)}) {
    c.inclination = bad;
    EXPECT_TRUE(refused(c, m, "inclination", "|alpha| < pi/2")) << bad;
  }
}

TEST(Command, SpinsWithinTheSpinLimitAndRotorFieldsOnlyWithARotor) {
  const Model plain = model_of("default"), gyro = model_of("gyro_reversal");
  Command c;
  c.spin = -kMaxSpin;
  EXPECT_EQ(validate(c, plain), "");
  c.spin = 1.01 * kMaxSpin;
  EXPECT_TRUE(refused(c, plain, "spin", "spin limit"));
  c = Command{};
  c.rotor_spin = 100.0;
  EXPECT_TRUE(refused(c, plain, "rotor_spin", "no rotor"));
  EXPECT_EQ(validate(c, gyro), "");
  c = Command{};
  c.rotor_coupling = -1e-9;
  EXPECT_TRUE(refused(c, gyro, "rotor_coupling", ">= 0"));
}

TEST(Command, RestitutionInTheUnitIntervalAndOnlyWithContactModes) {
  const Model m = model_of("hopping");
  Command c;
  c.restitution = 0.5;
  EXPECT_EQ(validate(c, m), "");
  c.restitution = 1.5;
  EXPECT_TRUE(refused(c, m, "restitution", "in [0, 1]"));
}

// mu_s must stay at or above mu(0) of the law in force after the command.
TEST(Command, StaticFrictionNotBelowTheLawsValueAtZeroSlip) {
  const Model m = model_of("coulomb");
  Command c;
  c.static_friction = 0.5 * friction_coefficient(m.friction, 0.0);
  EXPECT_TRUE(refused(c, m, "static_friction", ">= mu(0)"));
  c.static_friction = 2.0 * friction_coefficient(m.friction, 0.0);
  EXPECT_EQ(validate(c, m), "");
}

// physics.md section 12: each finite-contact field >= 0 and finite; none > 0 under the reduced model.
TEST(Command, FiniteContactFieldsNonNegativeAndNotUnderTheReducedModel) {
  const Model full = model_of("default");
  for (double bad : {-1e-4, double(NAN), double(INFINITY)}) {
    Command c;
    c.patch_radius = bad;  // and at most kMaxPatchRadius (1 m)
    EXPECT_TRUE(refused(c, full, "patch_radius", "in [0, 1] m")) << bad;
    c = Command{};
    c.drag = bad;
    EXPECT_TRUE(refused(c, full, "drag", ">= 0 and finite")) << bad;
  }
  Command c;
  c.rolling_resistance = 1e-5;
  EXPECT_EQ(validate(c, full), "");
  Model reduced = full;
  reduced.kind = ModelKind::adiabatic;
  EXPECT_TRUE(refused(c, reduced, "rolling_resistance", "adiabatic or auto"));
}

// A friction change is applied by the core over the law in force: the parameters it names change, the others
// (of this law and of the others) keep their values; a parameter of another law is refused, naming both.
TEST(Command, FrictionChangeAppliesOverTheLawInForce) {
  Model m = model_of("default");
  ASSERT_EQ(m.friction.kind, FrictionLawKind::paper);
  const FrictionLaw before = m.friction;
  Command c;
  c.friction = FrictionChange{};
  c.friction->given.emplace_back(find_friction_parameter("mu_c"), 0.5 * before.mu_c);  // no kind: the law's
  ASSERT_EQ(validate(c, m), "");
  StateVector y{};
  y[idx::f + 2] = 1.0;  // an upright top at rest: a pure law change touches no state
  const StateVector y_before = y;
  apply_command(c, m, y);
  EXPECT_EQ(m.friction.kind, FrictionLawKind::paper);
  EXPECT_EQ(m.friction.mu_c, 0.5 * before.mu_c);
  EXPECT_EQ(m.friction.s_c, before.s_c) << "not named: the law in force's";
  EXPECT_EQ(m.friction.mu, before.mu) << "another law's parameter: kept";
  EXPECT_EQ(y, y_before);

  Command coulomb;
  coulomb.friction = FrictionChange{FrictionLawKind::coulomb, {}, std::nullopt};
  ASSERT_EQ(validate(coulomb, m), "");
  apply_command(coulomb, m, y);
  EXPECT_EQ(m.friction.kind, FrictionLawKind::coulomb);
  EXPECT_EQ(m.friction.mu, before.mu) << "no parameter given: Coulomb with the mu in force";

  Command foreign;
  foreign.friction = FrictionChange{};
  foreign.friction->given.emplace_back(find_friction_parameter("s_c"), 0.5);
  EXPECT_EQ(validate(foreign, m), "friction.s_c: law coulomb reads mu");
  foreign.friction->given.clear();
  foreign.friction->points = std::vector<std::pair<double, double>>{{0.0, 0.1}, {1.0, 0.2}};
  EXPECT_EQ(validate(foreign, m), "friction.points: law coulomb reads mu");
  Command negative;
  negative.friction = FrictionChange{};
  negative.friction->given.emplace_back(find_friction_parameter("mu"), -0.1);
  EXPECT_TRUE(refused(negative, m, "friction.mu", ">= 0"));
}

// The schema's rows are the Command's number fields, in TOP_SIM_COMMAND_FIELDS order (the adapters copy fields with
// that list), and its limits are limits.hpp's.
TEST(CommandSchema, RowsAreTheCommandsFieldsWithTheLimitsOfLimitsHpp) {
  std::vector<std::pair<std::string, std::optional<double> Command::*>> listed;
#define TOP_SIM_LIST_FIELD(name) listed.emplace_back(#name, &Command::name);
  TOP_SIM_COMMAND_FIELDS(TOP_SIM_LIST_FIELD)
#undef TOP_SIM_LIST_FIELD
  ASSERT_EQ(listed.size(), command_fields().size());
  for (std::size_t i = 0; i < listed.size(); ++i) {
    EXPECT_EQ(listed[i].first, command_fields()[i].name);
    EXPECT_TRUE(listed[i].second == command_fields()[i].member) << listed[i].first;
    EXPECT_EQ(find_command_field(listed[i].first), &command_fields()[i]);
  }
  const CommandField& alpha = *find_command_field("inclination");
  EXPECT_EQ(alpha.range.upper, kMaxInclination);
  for (double a : {std::nextafter(kMaxInclination, 0.0), kMaxInclination, -kMaxInclination, 0.3, double(NAN)})
    EXPECT_EQ(alpha.range.admits(a), admissible_inclination(a)) << a;
  EXPECT_EQ(find_command_field("spin")->range.upper, kMaxSpin);
  EXPECT_TRUE(find_command_field("rotor_spin")->range.admits(-kMaxSpin));
  EXPECT_EQ(find_command_field("friction"), nullptr) << "the friction change has its own table";
}

// Each field just beyond its limit is refused naming the field, the value and the schema's range; at the limit
// (where it is closed) the range admits it.
TEST(CommandSchema, EachFieldBeyondItsLimitIsRefusedNamingFieldValueAndRange) {
  const Model gyro = model_of("gyro_reversal");  // a rotor: rotor_spin and rotor_coupling apply
  for (const CommandField& f : command_fields()) {
    const bool above = std::isfinite(f.range.upper);
    const double limit = above ? f.range.upper : f.range.lower;
    const double beyond = std::nextafter(limit, above ? INFINITY : -INFINITY);
    Command c;
    c.*f.member = beyond;
    EXPECT_EQ(validate(c, gyro), range_message(f.name, beyond, f.range_text)) << f.name;
    EXPECT_EQ(f.range.admits(limit), !(above ? f.range.upper_open : f.range.lower_open)) << f.name;
  }
}

// Scene events take every field of the schema and a friction change, applied at their time over the law in force.
TEST(CommandSchema, SceneEventsTakeEveryFieldAndAFrictionChange) {
  Simulator sim(top_sim_test::scene_from(top_sim_test::standard_scene(
      0.1, 200.0,
      "events:\n"
      "  - {t: 0.01, restitution: 0.2, static_friction: 0.3, drag: 1.0e-4}\n"
      "  - {t: 0.02, friction: {mu_c: 0.3}}\n"
      "  - {t: 0.03, friction: {law: coulomb, mu: 0.35}, static_friction: 0.4}\n")));
  sim.advance_to(0.015);
  EXPECT_EQ(sim.model().contact.restitution, 0.2);
  EXPECT_EQ(sim.model().air.drag, 1.0e-4);
  sim.advance_to(0.025);
  EXPECT_EQ(sim.model().friction.kind, FrictionLawKind::paper);
  EXPECT_EQ(sim.model().friction.mu_c, 0.3);
  EXPECT_EQ(sim.model().friction.s_c, 0.6) << "not named: the law in force's";
  sim.advance_to(0.035);
  EXPECT_EQ(sim.model().friction.kind, FrictionLawKind::coulomb);
  EXPECT_EQ(sim.model().friction.mu, 0.35);
  EXPECT_THROW(top_sim_test::scene_from(top_sim_test::standard_scene(
                   0.1, 200.0, "events:\n  - {t: 0.01, friction: {law: coulomb, s_c: 0.5}}\n")),
               SceneError)
      << "another law's parameter";
}
