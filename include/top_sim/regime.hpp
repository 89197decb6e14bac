// Regime classification published with the state (physics.md section 8).
#pragma once

#include <cstdint>

#include "top_sim/dynamics.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// The values are the regime codes of the messages (TopState.msg, top_state_t.lcm), whose adapters assert them.
// A tippe top (com_offset < 0, physics.md section 11) has its own regimes: upright, inverting, inverted, tumbling.
enum class Regime {
  nutating = 0,
  precessing = 1,
  sleeping = 2,
  sliding = 3,
  contact_fault = 4,
  upright = 5,
  inverting = 6,
  inverted = 7,
  tumbling = 8,
};
constexpr int kRegimeCount = 9;  // the indexes of per-regime arrays (the summary's regime_seconds)

constexpr std::uint8_t code(Regime r) { return static_cast<std::uint8_t>(r); }
const char* to_string(Regime r);

// The quantities the classification reads.
struct RegimeIndicators {
  double nutation_angle = 0.0;  // angle between omega (or L_total for a gyrostat) and f_hat [rad]
  double nutation_rate = 0.0;   // its time derivative [rad/s]
  double acceleration = 0.0;    // |a_cm| [m/s^2]
  double speed = 0.0;           // |v_cm| [m/s]
  bool runaway = false;         // no stationary state, or slip beyond the unstable root
  bool tippe = false;           // a tippe top (com_offset < 0): classified by its tilt
  double tilt = 0.0;            // angle of f_hat from the plane normal [rad]
  double slip = 0.0;            // relative slip s of the contact (physics.md section 3)
};

// A tippe top's regime from its tilt: upright and inverted within kTippeEndTilt of 0 and pi; in between tumbling
// while the contact hardly slips (s < kTippeGlidingSlip: the final states are gliding-free, physics.md section 11),
// inverting while it slips. Not the tilt's rate: a tumbling top nutates (+-0.04 rad at 8.7 Hz) for minutes.
constexpr double kTippeEndTilt = 0.5;        // [rad]
constexpr double kTippeGlidingSlip = 2e-3;   // relative slip s

// `dyn` is the dynamics of y and `stationary` the sleeping state at y's shell spin (each computed once by the caller).
RegimeIndicators regime_indicators(const Model& model, const StateVector& y, const Dynamics& dyn,
                                   const StationaryState& stationary);

// `previous` adds hysteresis: a sleeping top stays asleep until its path turns at twice the threshold,
// so the regime does not flicker while the last precession dies out.
Regime classify(const RegimeThresholds& thresholds, const RegimeIndicators& ind, bool fault,
                Regime previous = Regime::nutating);

}  // namespace top_sim
