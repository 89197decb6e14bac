// Fixed-step methods: Euler and RK4 from Boost.Odeint, semi-implicit Euler here, the implicit midpoint rules
// (implicit_midpoint.cpp); one time keeping for all of them.
#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "implicit_midpoint.hpp"
#include "steppers.hpp"

namespace top_sim {

namespace odeint = boost::numeric::odeint;

namespace {

// Counts right-hand-side calls and adapts the odeint calling convention.
struct CountingSystem {
  const System* system;
  std::uint64_t* counter;
  void operator()(const StateVector& x, StateVector& dxdt, double /*t*/) const {
    ++*counter;
    (*system)(x, dxdt);
  }
};

class FixedStepper : public Stepper {
 public:
  FixedStepper(Method method, double dt, System system, DifferenceSteps difference_steps = {}, Azimuth azimuth = {})
      : method_(method),
        dt_(dt),
        system_(std::move(system)),
        midpoint_(std::move(difference_steps),
                  method == Method::fitted_midpoint ? std::move(azimuth) : Azimuth{}, method == Method::fitted_midpoint) {}

  void reset(const StateVector& y, double t) override {
    y_ = y;
    y_prev_ = y;
    t_ = t;
    t_prev_ = t;
    t_base_ = t;
    n_since_base_ = 0;
    midpoint_.reset();
  }

  void step(double t_limit) override {
    double h = dt_;
    // Time is t_base_ + n dt (one rounding, not a sum of n): a run sampled at multiples of dt makes its steps.
    double t_next = t_base_ + static_cast<double>(n_since_base_ + 1) * dt_;
    // Land exactly on t_limit (publish instants, events); a full step that ends within rounding of it lands on it
    // with h = dt (no extra step of a few ulps, the same steps sampled or not: the rates do not read t).
    const double slack = 16.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_limit), dt_);
    const bool lands = t_limit > t_ && t_limit - t_ < h + slack;
    if (lands) {
      if (t_limit - t_ < h - slack) h = t_limit - t_;
      t_next = t_limit;
    }
    y_prev_ = y_;
    t_prev_ = t_;
    CountingSystem sys{&system_, &stats.rhs_evaluations};
    switch (method_) {
      case Method::euler: euler_.do_step(sys, y_, t_, h); break;
      case Method::rk4: rk4_.do_step(sys, y_, t_, h); break;
      case Method::semi_implicit_euler: semi_implicit_step(sys, h); break;
      case Method::implicit_midpoint:
      case Method::fitted_midpoint: midpoint_.step(system_, stats.rhs_evaluations, y_, t_, h); break;
      default: throw std::logic_error("FixedStepper: not a fixed-step method");
    }
    normalize_figure_axis(y_);
    if (lands) {
      t_base_ = t_limit;
      n_since_base_ = 0;
    } else {
      ++n_since_base_;
    }
    t_ = t_next;
    last_h_ = h;
    ++stats.steps;
  }

  double time() const override { return t_; }
  double previous_time() const override { return t_prev_; }
  const StateVector& state() const override { return y_; }
  double last_step_size() const override { return last_h_; }

  // Linear interpolation: fixed-step runs land on requested times, this serves only event location.
  void state_at(double t, StateVector& y) const override {
    const double span = t_ - t_prev_;
    const double w = span > 0.0 ? (t - t_prev_) / span : 1.0;
    for (std::size_t i = 0; i < y.size(); ++i) y[i] = (1.0 - w) * y_prev_[i] + w * y_[i];
  }

 private:
  // Velocities (u, omega, nu, W, gap rate) first from the old state, then positions (p, f_hat, psi, gap) with the
  // new velocities.
  void semi_implicit_step(const CountingSystem& sys, double h) {
    StateVector d;
    sys(y_, d, t_);
    for (std::size_t i : {idx::u, idx::u + 1, idx::omega, idx::omega + 1, idx::omega + 2, idx::nu, idx::w_diss,
                          idx::gap_rate})
      y_[i] += h * d[i];
    sys(y_, d, t_);  // position rates with the new velocities (their own velocity rates are unused)
    for (std::size_t i : {idx::x, idx::x + 1, idx::f, idx::f + 1, idx::f + 2, idx::psi, idx::gap}) y_[i] += h * d[i];
  }

  Method method_;
  double dt_;
  System system_;
  StateVector y_{}, y_prev_{};
  double t_ = 0.0, t_prev_ = 0.0, last_h_ = 0.0;
  double t_base_ = 0.0;               // the last landing (reset or t_limit): time is t_base_ + n_since_base_ dt
  std::uint64_t n_since_base_ = 0;
  odeint::euler<StateVector> euler_;
  odeint::runge_kutta4<StateVector> rk4_;
  ImplicitMidpoint midpoint_;
};

}  // namespace

std::unique_ptr<Stepper> make_fixed_stepper(Method method, double dt, System system, DifferenceSteps difference_steps,
                                            Azimuth azimuth) {
  return std::make_unique<FixedStepper>(method, dt, std::move(system), std::move(difference_steps),
                                        std::move(azimuth));
}
}  // namespace top_sim
