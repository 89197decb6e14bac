// Regime classification published with the state (physics.md section 8).
#pragma once

#include <cstdint>

#include "top_sim/contact.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// The values are the regime codes of the messages (TopState.msg, top_state_t.lcm), whose adapters assert them.
// A tippe top (com_offset < 0, physics.md section 11) has its own regimes: upright, inverting, inverted, tumbling.
// A body of shapes says what touches (section 8): rolling (on a rim, or on two shapes as a cone), on_crown (a rim
// that is not its first shape), on_stem (a sphere that is not its first); the end states end a run's regime.
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
  rolling = 9,
  on_crown = 10,
  on_stem = 11,
  at_rest = 12,
  lying_flat = 13,
  fallen = 14,
};
constexpr int kRegimeCount = 15;  // the indexes of per-regime arrays (the summary's regime_seconds)

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
  bool shape_body = false;      // a rim or several shapes (has_shapes): classified by what touches
  std::uint32_t touching = 0;   // bit i: shape i touches (Snapshot::touching; 0 in flight)
  std::uint32_t touching_rims = 0;  // the touching shapes that are rims
};

// A tippe top's regime from its tilt: upright and inverted within kTippeEndTilt of 0 and pi; in between tumbling
// while the contact hardly slips (s < kTippeGlidingSlip: the final states are gliding-free, physics.md section 11),
// inverting while it slips. Not the tilt's rate: a tumbling top nutates (+-0.04 rad at 8.7 Hz) for minutes.
constexpr double kTippeEndTilt = 0.5;        // [rad]
constexpr double kTippeGlidingSlip = 2e-3;   // relative slip s

// `dyn` is the dynamics of y in `mode` and `stationary` the sleeping state at y's shell spin (each computed once by
// the caller).
RegimeIndicators regime_indicators(const Model& model, ContactMode mode, const StateVector& y, const Dynamics& dyn,
                                   const StationaryState& stationary);

// The regime word of a run that has stopped at an end state (none: the end state is none).
Regime end_regime(EndState state);

// `previous` adds hysteresis: a sleeping top stays asleep until its path turns at twice the threshold,
// so the regime does not flicker while the last precession dies out.
Regime classify(const RegimeThresholds& thresholds, const RegimeIndicators& ind, bool fault,
                Regime previous = Regime::nutating);

}  // namespace top_sim
