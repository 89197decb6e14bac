// Dormand-Prince 5(4) with dense output, computed as odeint computes it (its operations, our storage), and its PI
// step-size control: the stepper of `method: dopri5` and the explicit half of `switching`.
#pragma once

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cstdint>

#include "top_sim/integrators.hpp"

namespace top_sim {

namespace odeint = boost::numeric::odeint;

// odeint's default error norm over every component but the spin phase (physics.md section 2).
class PhaseFreeErrorChecker {
 public:
  PhaseFreeErrorChecker(double atol = 1e-6, double rtol = 1e-6) : atol_(atol), rtol_(rtol) {}

  template <class Algebra>
  double error(Algebra&, const StateVector& x_old, const StateVector& dxdt_old, StateVector& x_err, double dt) const {
    double err = 0.0;
    for (std::size_t i = 0; i < idx::psi; ++i) {
      const double scale = atol_ + rtol_ * (std::abs(x_old[i]) + std::abs(dt) * std::abs(dxdt_old[i]));
      err = std::max(err, std::abs(x_err[i]) / scale);
    }
    return err;
  }

 private:
  double atol_, rtol_;
};

// The PI step-size control of Hairer's DOPRI5 (Hairer, Norsett & Wanner, Solving ODEs I, section II.4, and its
// code): the new step reads this step's error and the last accepted one's, which damps the accept/reject cycling of
// a stability-limited step; after a rejection the next accepted step does not grow. It counts rejections.
struct PiMemory {
  double error = 1e-4;    // the last accepted step's error (Hairer's facold)
  bool rejected = false;  // the last try was rejected
  std::uint64_t* rejections = nullptr;
};

class PiAdjuster : public odeint::default_step_adjuster<double, double> {
  // Hairer's beta (0.04 in DOPRI5, up to 0.08 advised): 0.08 errs less on the default scene than odeint's control and
  // 0.04 (docs/performance.md, "Lean step, continued"); 0 would be plain I control.
  static constexpr double kBeta = 0.08;
  static constexpr double kExponent = 0.2 - 0.75 * kBeta;  // 1/5 less the part the last error takes
  static constexpr double kSafety = 0.9;
  static constexpr double kMinFactor = 0.2, kMaxFactor = 10.0;  // bounds of h_new / h

 public:
  explicit PiAdjuster(double max_dt = 0.0, PiMemory* memory = nullptr)
      : odeint::default_step_adjuster<double, double>(max_dt), memory_(memory) {}
  double decrease_step(double dt, double error, int /*error_order*/) const {
    ++*memory_->rejections;
    memory_->rejected = true;
    return limited(dt * std::max(kMinFactor, kSafety / std::pow(error, kExponent)));
  }
  double increase_step(double dt, double error, int /*stepper_order*/) const {
    const double factor = kSafety * std::pow(memory_->error, kBeta) / std::pow(error, kExponent);
    double h = dt * std::clamp(factor, kMinFactor, kMaxFactor);
    if (memory_->rejected) h = std::min(h, dt);
    memory_->error = std::max(error, 1e-4);
    memory_->rejected = false;
    return limited(h);
  }

 private:
  double limited(double dt) const { return m_max_dt > 0.0 ? std::min(dt, m_max_dt) : dt; }
  PiMemory* memory_;
};

struct Dopri5Scratch;  // the stages that live only inside one step (dopri5.cpp)

// odeint's dense-output, controlled, first-same-as-last dopri5 (runge_kutta_dopri5 in dense_output_runge_kutta of
// controlled_runge_kutta) with the same operations in the same order through the same algebra, so the same bits;
// its per-top storage is what a step leaves for the next and for the dense output: the two states and derivatives
// (toggled), k3 to k6 (960 bytes, 15 cache lines; odeint's objects held 2032 bytes).
class Dopri5Stepper final : public Stepper {
  using Ops = odeint::default_operations;

 public:
  Dopri5Stepper(const IntegratorSettings& s, System system)
      : system_(std::move(system)),
        memory_{1e-4, false, &stats.rejected},
        checker_(s.atol, s.rtol),
        adjuster_(s.max_dt, &memory_),
        settings_(s) {}
  Dopri5Stepper(const Dopri5Stepper&) = delete;  // the controller points at this object's stats
  Dopri5Stepper& operator=(const Dopri5Stepper&) = delete;

  void reset(const StateVector& y, double t) override { reset(y, t, next_dt_ > 0.0 ? next_dt_ : settings_.dt); }
  void reset(const StateVector& y, double t, double dt) {
    x_[current_] = y;
    t_ = t;
    dt_ = dt;
    derivative_ready_ = false;
    memory_.error = 1e-4;  // a new start: no error history
    memory_.rejected = false;
    renormalized_ = false;
    restarted_ = true;
  }
  double next_step_size() const { return next_dt_; }
  // Every try, accepted or not, ends with the system at its new state: after an accepted step that was not
  // renormalised, state() is the last argument.
  bool state_was_last_rhs() const override { return !restarted_ && !renormalized_; }

  void step(double) override;

  double time() const override { return t_; }
  // After reset() the last step's interval is kept (as odeint's initialize() keeps it): there is none to offer.
  double previous_time() const override { return restarted_ ? time() : t_old_; }
  const StateVector& state() const override { return x_[current_]; }
  double last_step_size() const override { return time() - previous_time(); }

  void state_at(double t, StateVector& y) const override;

 private:
  static constexpr int kMaxTries = 500;

  void rhs(const StateVector& x, StateVector& dxdt) {
    ++stats.rhs_evaluations;
    system_(x, dxdt);
  }

  // controlled_runge_kutta::try_step (first same as last): writes the other state and derivative; on success
  // advances t_; either way dt_ is the next try's step.
  bool try_step(Dopri5Scratch& s);

  // runge_kutta_dopri5::calc_state: the continuous extension over the last step.
  void interpolate(double t, StateVector& y) const;

  // f_hat back to unit length in place, and the first-same-as-last derivative with it (no re-initialisation): only
  // f' = omega x f reads |f| (the model reads f_hat normalised) and it is linear in f, so f' / |f| is what the
  // re-evaluation would give, to rounding; the last step's interpolant at its end (theta = 1) does not read it.
  void renormalize(StateVector& y, double n2);

  // The 5th-order weights (also the dense output's at theta = 1).
  static constexpr double kC1 = 35.0 / 384.0, kC3 = 500.0 / 1113.0, kC4 = 125.0 / 192.0, kC5 = -2187.0 / 6784.0,
                          kC6 = 11.0 / 84.0;

  // What every step reads and writes, in 18 cache lines: the scalars and the controller next to the object's
  // header, then the stored stages in 15 aligned lines.
  int current_ = 0;  // x_[current_] is the state at t_; the other is the last step's start (or a try's output)
  bool derivative_ready_ = false;
  bool renormalized_ = false;
  bool restarted_ = true;  // no step since reset()
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0;
  double next_dt_ = 0.0;
  System system_;
  PiMemory memory_;  // before adjuster_: it points here
  PhaseFreeErrorChecker checker_;
  PiAdjuster adjuster_;
  alignas(64) std::array<StateVector, 2> x_{};
  std::array<StateVector, 2> dxdt_{};
  StateVector k3_{}, k4_{}, k5_{}, k6_{};
  IntegratorSettings settings_;  // read at resets
};

}  // namespace top_sim
