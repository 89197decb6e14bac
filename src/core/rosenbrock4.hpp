// Rosenbrock 4 (stiff) from Boost.Odeint with a central-difference Jacobian and the spin phase out of its error
// estimate: the stepper of `method: rosenbrock4`, of the stiff layer, and the stiff half of `switching`.
#pragma once

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/ublas/matrix.hpp>
#include <boost/numeric/ublas/vector.hpp>
#include <cstdint>

#include "top_sim/integrators.hpp"

namespace top_sim {

namespace odeint = boost::numeric::odeint;

using UVector = boost::numeric::ublas::vector<double>;
using UMatrix = boost::numeric::ublas::matrix<double>;

// odeint's Rosenbrock 4 with the spin phase excluded from its error estimate; counts the steps its controller tries.
class PhaseFreeRosenbrock4 : public odeint::rosenbrock4<double> {
 public:
  explicit PhaseFreeRosenbrock4(std::uint64_t* attempts = nullptr) : attempts_(attempts) {}
  using odeint::rosenbrock4<double>::do_step;
  template <class System>
  void do_step(System system, const state_type& x, time_type t, state_type& xout, time_type dt, state_type& xerr) {
    if (attempts_) ++*attempts_;
    odeint::rosenbrock4<double>::do_step(system, x, t, xout, dt, xerr);
    xerr[idx::psi] = 0.0;
  }

 private:
  std::uint64_t* attempts_;
};

class Rosenbrock4Stepper final : public Stepper {
  using Controller = odeint::rosenbrock4_controller<PhaseFreeRosenbrock4>;
  using Dense = odeint::rosenbrock4_dense_output<Controller>;

  struct Rhs {
    Rosenbrock4Stepper* self;
    void operator()(const UVector& x, UVector& dxdt, double) const;
  };
  // Central differences: Rosenbrock methods lose order with an inexact Jacobian, and forward differences at
  // 1e-9 relative (round-off ~1e-7) made 8x more steps on the default scene (docs/performance.md).
  struct Jacobian {
    Rosenbrock4Stepper* self;
    void operator()(const UVector& x, UMatrix& jac, double, UVector& dfdt) const;
  };

 public:
  Rosenbrock4Stepper(const IntegratorSettings& s, System system, DifferenceSteps difference_steps = {})
      : settings_(s),
        system_(std::move(system)),
        difference_steps_(std::move(difference_steps)),
        dense_{Dense(Controller(s.atol, s.rtol, s.max_dt, PhaseFreeRosenbrock4(&attempts_))),
               Dense(Controller(s.atol, s.rtol, s.max_dt, PhaseFreeRosenbrock4(&attempts_)))},
        x_(idx::size) {}
  Rosenbrock4Stepper(const Rosenbrock4Stepper&) = delete;  // the steppers point at this object's attempt count
  Rosenbrock4Stepper& operator=(const Rosenbrock4Stepper&) = delete;

  void reset(const StateVector& y, double t) override { reset(y, t, next_dt_ > 0.0 ? next_dt_ : settings_.dt); }
  void reset(const StateVector& y, double t, double dt) {
    std::copy(y.begin(), y.end(), x_.begin());
    current().initialize(x_, t, dt);
    renormalized_ = false;
    restarted_ = true;
    copy_current();
  }

  void step(double) override;

  double time() const override { return dense_[active_].current_time(); }
  // After reset() odeint keeps the last step's interval (initialize() does not clear it): there is none to offer.
  double previous_time() const override { return restarted_ ? time() : interval().previous_time(); }
  const StateVector& state() const override { return current_; }
  double last_step_size() const override { return time() - previous_time(); }
  double next_step_size() const { return next_dt_; }

  void state_at(double t, StateVector& y) const override;

 private:
  Dense& current() { return dense_[active_]; }
  void copy_current() { std::copy(current().current_state().begin(), current().current_state().end(), current_.begin()); }
  Dense& interval() const { return dense_[renormalized_ ? 1 - active_ : active_]; }  // odeint's calc_state is non-const

  IntegratorSettings settings_;
  System system_;
  DifferenceSteps difference_steps_;
  std::uint64_t attempts_ = 0;  // steps tried by either twin's controller
  mutable Dense dense_[2];
  int active_ = 0;
  UVector x_;
  mutable UVector scratch_ = UVector(idx::size);  // dense output's state: a read allocates nothing
  StateVector current_{};
  double next_dt_ = 0.0;
  bool renormalized_ = false;
  bool restarted_ = true;  // no step since reset()
};

}  // namespace top_sim
