// The dopri5 / rosenbrock4 switch (`method: switching`).
#include <algorithm>

#include "dopri5.hpp"
#include "rosenbrock4.hpp"
#include "steppers.hpp"

namespace top_sim {

namespace {

// Runs dopri5 and now and then probes rosenbrock4 from the current state; keeps whichever advances more simulated
// time per unit of cost. The cost model is deterministic (right-hand sides plus a per-step overhead in right-hand-side
// equivalents, from bench/core_bench.cpp) so that runs are repeatable.
class SwitchingStepper : public Stepper {
  static constexpr double kExplicitOverhead = 1.0;   // dopri5 bookkeeping per step [RHS equivalents]
  static constexpr double kStiffOverhead = 110.0;    // rosenbrock4 LU solve and ublas copies per step (7 us - 24 RHS)
  static constexpr double kMargin = 1.5;             // hysteresis: a switch must pay at least this factor
  static constexpr std::uint64_t kFirstProbe = 200;  // dopri5 steps before the first rosenbrock4 probe
  static constexpr std::uint64_t kMaxProbe = 3200;   // the probe interval doubles after each failed probe
  static constexpr std::uint64_t kProbeSteps = 6;    // rosenbrock4 steps of a probe (its step grows 5x per step)
  static constexpr std::uint64_t kStiffWindow = 16;  // rosenbrock4 steps between checks of its rate

 public:
  SwitchingStepper(const IntegratorSettings& s, System system, DifferenceSteps difference_steps)
      : explicit_(s, system), stiff_(s, std::move(system), std::move(difference_steps)) {}

  void reset(const StateVector& y, double t) override {
    stiff_active_ = false;
    probing_ = false;
    switch_pending_ = false;
    probe_interval_ = kFirstProbe;
    explicit_rate_ = 0.0;
    explicit_.reset(y, t);
    clear_window();
  }

  void step(double t_limit) override {
    if (switch_pending_) do_switch();
    Stepper& a = active();
    const StepperStats before = a.stats;
    a.step(t_limit);
    const std::uint64_t steps = a.stats.steps - before.steps;
    const std::uint64_t rhs = a.stats.rhs_evaluations - before.rhs_evaluations;
    stats.steps += steps;
    stats.rejected += a.stats.rejected - before.rejected;
    stats.rhs_evaluations += rhs;
    window_time_ += a.time() - a.previous_time();
    window_cost_ += static_cast<double>(rhs) + static_cast<double>(steps) * (stiff_active_ ? kStiffOverhead : kExplicitOverhead);
    window_steps_ += steps;
    decide();
  }

  double time() const override { return active().time(); }
  double previous_time() const override { return active().previous_time(); }
  const StateVector& state() const override { return active().state(); }
  void state_at(double t, StateVector& y) const override { active().state_at(t, y); }
  double last_step_size() const override { return active().last_step_size(); }
  bool state_was_last_rhs() const override { return active().state_was_last_rhs(); }
  bool stiff_active() const { return stiff_active_; }

 private:
  const Stepper& active() const { return stiff_active_ ? static_cast<const Stepper&>(stiff_) : explicit_; }
  Stepper& active() { return stiff_active_ ? static_cast<Stepper&>(stiff_) : explicit_; }
  void clear_window() {
    window_time_ = window_cost_ = 0.0;
    window_steps_ = 0;
  }

  void decide() {
    if (!stiff_active_) {
      if (window_steps_ < probe_interval_) return;
      explicit_rate_ = window_time_ / window_cost_;
      probing_ = true;
      switch_pending_ = true;
    } else if (probing_) {
      if (window_steps_ < kProbeSteps) return;
      // The probe's first steps ramp up from dopri5's step: judge it by the step its controller proposes now.
      const double stiff_rate = stiff_.next_step_size() / (window_cost_ / static_cast<double>(window_steps_));
      probing_ = false;
      if (stiff_rate > kMargin * explicit_rate_) {
        probe_interval_ = kFirstProbe;
      } else {
        probe_interval_ = std::min(2 * probe_interval_, kMaxProbe);
        switch_pending_ = true;
      }
    } else {
      if (window_steps_ < kStiffWindow) return;
      // A new transient (the top woke up): back to dopri5 once rosenbrock4 no longer pays.
      if (window_time_ / window_cost_ * kMargin < explicit_rate_) switch_pending_ = true;
    }
    clear_window();
  }

  void do_switch() {
    switch_pending_ = false;
    const StateVector y = active().state();
    const double t = active().time();
    if (stiff_active_) {
      explicit_.reset(y, t);
    } else {
      const double h = explicit_.next_step_size() > 0.0 ? explicit_.next_step_size() : explicit_.last_step_size();
      stiff_.reset(y, t, 2.0 * h);
    }
    stiff_active_ = !stiff_active_;
    clear_window();
  }

  Dopri5Stepper explicit_;
  Rosenbrock4Stepper stiff_;
  bool stiff_active_ = false, probing_ = false, switch_pending_ = false;
  std::uint64_t probe_interval_ = kFirstProbe, window_steps_ = 0;
  double window_time_ = 0.0, window_cost_ = 0.0, explicit_rate_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_switching_stepper(const IntegratorSettings& settings, System system,
                                                DifferenceSteps difference_steps) {
  return std::make_unique<SwitchingStepper>(settings, std::move(system), std::move(difference_steps));
}
}  // namespace top_sim
