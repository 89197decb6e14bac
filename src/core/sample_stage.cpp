// The Simulator's sample stage: the committed state's analysis (sample.hpp), made on the first read after a commit,
// and the snapshot a reader gets of it (physics.md section 10 for the regime).
#include <cstring>

#include "simulator_impl.hpp"

namespace top_sim {

// The sample of the committed state, analysed on the first read after a commit or a regime point and classified
// with the hysteresis of the last point (a read commits nothing: the next read or point sees the same history).
const SampleAnalysis& SimulatorImpl::sample() const {
  if (sample_.revision != revision_ || sample_.point != cadence_k_) {
    // The tick's end was just scanned, with a full evaluation: its dynamics and energy serve (the same bits).
    const bool scanned = scan_end_.valid && sample_.staged && scan_end_.t == t_ &&
                         std::memcmp(scan_end_.y.data(), y_.data(), sizeof(StateVector)) == 0;
    sample_.analysis = scanned ? analyse_sample(model_, mode_, y_, stationary_geometry_,
                                                sample_.analysis.dynamics, scan_end_.energy)
                               : analyse_sample(model_, mode_, y_, stationary_geometry_);
    sample_.staged = false;
    sample_.regime = classify(model_.regime, sample_.analysis.indicators, false, cadence_regime_);
    sample_.revision = revision_;
    sample_.point = cadence_k_;
  }
  return sample_.analysis;
}

Snapshot SimulatorImpl::snapshot() const {
  const SampleAnalysis& a = sample();
  const Regime regime = fault_ != ContactFault::none        ? Regime::contact_fault
                        : end_state_ != EndState::none ? end_regime(end_state_)
                                                       : sample_.regime;
  Snapshot s = make_snapshot(model_, stationary_geometry_, y_, t_, balance_, a, regime, mode_);
  if (fault_ != ContactFault::none) {
    s.fault = fault_;
    s.fault_message = fault_message_;
  }
  if (end_state_ != EndState::none) {
    s.end_state = end_state_;
    s.end_message = end_message_;
  }
  return s;
}

}  // namespace top_sim
