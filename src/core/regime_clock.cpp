// The regime clock: the top's regime classified at t_reset + k kRegimeCadence on the dense output, whoever reads
// (physics.md section 10), the seconds in each regime, and the overflow guard a run nobody reads still needs.
#include <algorithm>
#include <cmath>

#include "simulator_impl.hpp"
#include "top_sim/simulator.hpp"  // its public constants: the regime cadence

namespace top_sim {

// The regime points in (cadence_t_, t_end], each on the dense output of the step that holds it.
void SimulatorImpl::run_cadence(double t_end) {
  while (!stopped() && !handover_due_) {
    const double tk = t_origin_ + static_cast<double>(cadence_k_ + 1) * Simulator::kRegimeCadence;
    if (tk > t_end) return;
    ++cadence_k_;
    StateVector yk;
    if (tk >= stepper_->time()) yk = stepper_->state(); else stepper_->state_at(tk, yk);
    cadence_point(tk, yk);
  }
}

// One regime point: the overflow guard and the classification that carries the hysteresis; the interval since the
// last point counts for that point's regime. Under auto a sleeping top may hand over here.
void SimulatorImpl::cadence_point(double t, const StateVector& y) {
  const SampleAnalysis a = regime_point_analysis(model_, mode_, y, stationary_geometry_.state);
  // A finite state whose energy or dynamics overflow (spins ~1e150 rad/s and up) is no answer either.
  if (const char* part = overflowed_part(a)) {
    commit(y, t);  // the top stops at the point that overflowed
    fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t) + " (" + part + " overflowed)");
    return;
  }
  regime_seconds_[code(cadence_regime_)] += t - cadence_t_;
  cadence_t_ = t;
  cadence_regime_ = classify(model_.regime, a.indicators, false, cadence_regime_);
  if (model_.automatic.enabled && model_.kind == ModelKind::full && mode_ == ContactMode::slipping &&
      (cadence_regime_ == Regime::sleeping || cadence_regime_ == Regime::precessing))
    consider_handover(t, y);
}

// Every regime point of the reduced model classifies asleep (no nutation, no acceleration): counted, not analysed.
void SimulatorImpl::skip_cadence(double t_end) {
  std::uint64_t k = cadence_k_;
  const auto point = [this](std::uint64_t i) { return t_origin_ + static_cast<double>(i) * Simulator::kRegimeCadence; };
  const double steps = std::floor((t_end - t_origin_) / Simulator::kRegimeCadence);
  if (steps > static_cast<double>(k) + 1.0) k = static_cast<std::uint64_t>(steps) - 1;
  while (point(k + 1) <= t_end) ++k;  // the same points as run_cadence's, to the bit
  if (k == cadence_k_) return;
  const double first = point(cadence_k_ + 1), last = point(k);
  regime_seconds_[code(cadence_regime_)] += first - cadence_t_;
  regime_seconds_[code(Regime::sleeping)] += last - first;
  cadence_regime_ = Regime::sleeping;
  cadence_t_ = last;
  cadence_k_ = k;
}

std::array<double, kRegimeCount> SimulatorImpl::regime_seconds() const {
  std::array<double, kRegimeCount> s = regime_seconds_;
  s[code(cadence_regime_)] += std::max(0.0, t_ - cadence_t_);  // up to now (a fault stops the time)
  return s;
}

}  // namespace top_sim
