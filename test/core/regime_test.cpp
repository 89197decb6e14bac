// The regime classification of physics.md section 8, from its indicators (no simulation).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "top_sim/regime.hpp"

using namespace top_sim;

namespace {

const RegimeThresholds kThresholds;

RegimeIndicators resting() { return RegimeIndicators{}; }

}  // namespace

TEST(Regime, AFaultOutranksEveryIndicator) {
  RegimeIndicators ind = resting();
  ind.runaway = true;
  ind.nutation_angle = 1.0;
  EXPECT_EQ(classify(kThresholds, ind, true), Regime::contact_fault);
  ind.tippe = true;
  EXPECT_EQ(classify(kThresholds, ind, true), Regime::contact_fault);
}

TEST(Regime, SlidingOutranksNutation) {
  RegimeIndicators ind = resting();
  ind.runaway = true;
  ind.nutation_angle = 10 * kThresholds.nutation_angle;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::sliding);
}

TEST(Regime, NutatingAboveEitherNutationThreshold) {
  RegimeIndicators ind = resting();
  ind.nutation_angle = 1.01 * kThresholds.nutation_angle;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::nutating);
  ind = resting();
  ind.nutation_rate = -1.01 * kThresholds.nutation_rate;  // either sign
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::nutating);
  ind.nutation_rate = 0.99 * kThresholds.nutation_rate;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::sleeping);
}

// A straight path (|a_cm| below the floor, or below turn_rate x speed) sleeps; a turning one precesses.
TEST(Regime, SleepingOnAStraightPathPrecessingOnATurningOne) {
  RegimeIndicators ind = resting();
  ind.speed = 0.01;
  ind.acceleration = 0.9 * kThresholds.sleep_turn_rate * ind.speed;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::sleeping);
  ind.acceleration = 1.1 * kThresholds.sleep_turn_rate * ind.speed;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::precessing);
  ind.speed = 0.0;  // at rest: only the floor counts
  ind.acceleration = 0.9 * kThresholds.sleep_acceleration;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::sleeping);
}

// Hysteresis: a sleeping top stays asleep until its path turns at twice the threshold.
TEST(Regime, ASleepingTopWakesOnlyAtTwiceTheThreshold) {
  RegimeIndicators ind = resting();
  ind.speed = 0.01;
  ind.acceleration = 1.5 * kThresholds.sleep_turn_rate * ind.speed;
  EXPECT_EQ(classify(kThresholds, ind, false, Regime::precessing), Regime::precessing);
  EXPECT_EQ(classify(kThresholds, ind, false, Regime::sleeping), Regime::sleeping);
  ind.acceleration = 2.1 * kThresholds.sleep_turn_rate * ind.speed;
  EXPECT_EQ(classify(kThresholds, ind, false, Regime::sleeping), Regime::precessing);
}

// A tippe top by its tilt: upright and inverted within kTippeEndTilt of 0 and pi; between, inverting while it slips
// and tumbling while it hardly does (5 times the slip bound to leave tumbling).
TEST(Regime, TippeTopByItsTiltAndSlip) {
  RegimeIndicators ind = resting();
  ind.tippe = true;
  ind.nutation_angle = 1.0;  // a tippe top's regime ignores nutation
  ind.tilt = 0.9 * kTippeEndTilt;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::upright);
  ind.tilt = M_PI - 0.9 * kTippeEndTilt;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::inverted);
  ind.tilt = M_PI / 2;
  ind.slip = 2.0 * kTippeGlidingSlip;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::inverting);
  EXPECT_EQ(classify(kThresholds, ind, false, Regime::tumbling), Regime::tumbling);
  ind.slip = 0.5 * kTippeGlidingSlip;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::tumbling);
}

// The codes are the message constants 0 to 14 (TopState.msg, top_state_t.lcm), each with its own name.
TEST(Regime, CodesAreTheMessageConstantsWithDistinctNames) {
  std::set<std::string> names;
  for (int i = 0; i < kRegimeCount; ++i) {
    const Regime r = static_cast<Regime>(i);
    EXPECT_EQ(code(r), i);
    names.insert(to_string(r));
  }
  EXPECT_EQ(names.size(), static_cast<std::size_t>(kRegimeCount));
  EXPECT_STREQ(to_string(Regime::sleeping), "sleeping");
}

// A body of shapes says what touches before any tip-sphere word (physics.md section 8): two shapes, or its first
// shape when that is a rim, roll; a rim or sphere that is not its first shape is its crown or stem; on its first
// sphere or in flight the tip sphere's (or a tippe top's) words hold.
TEST(Regime, ABodyOfShapesSaysWhatTouches) {
  RegimeIndicators ind = resting();
  ind.shape_body = true;
  ind.runaway = true;  // would be sliding on the tip sphere
  ind.touching = 0b11;
  ind.touching_rims = 0b10;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::rolling);  // tip and crown
  ind.touching = ind.touching_rims = 0b1;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::rolling);  // a disc on its edge
  ind.touching = ind.touching_rims = 0b10;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::on_crown);
  ind.touching = 0b10;
  ind.touching_rims = 0;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::on_stem);
  ind.touching = 0b1;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::sliding);  // on its tip sphere: the tip's words
  ind.touching = 0;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::sliding);  // in flight too
  ind.tippe = true;
  ind.tilt = M_PI / 2;
  ind.slip = 1.0;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::inverting);  // a tippe top on its ball, by its tilt
  ind.touching = 0b10;
  EXPECT_EQ(classify(kThresholds, ind, false), Regime::on_stem);
  EXPECT_EQ(classify(kThresholds, ind, true), Regime::contact_fault);  // a fault outranks what touches
}

TEST(Regime, EndStatesHaveTheirOwnWords) {
  EXPECT_EQ(end_regime(EndState::at_rest), Regime::at_rest);
  EXPECT_EQ(end_regime(EndState::lying_flat), Regime::lying_flat);
  EXPECT_EQ(end_regime(EndState::fallen), Regime::fallen);
  for (EndState e : {EndState::at_rest, EndState::lying_flat, EndState::fallen})
    EXPECT_STREQ(to_string(end_regime(e)), to_string(e)) << "the end regime and the end state share their word";
}
