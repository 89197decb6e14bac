// Rosenbrock 4: the odeint dense-output stepper and its twin (for renormalised states), and the Jacobian.
#include "rosenbrock4.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace top_sim {

// Relative central-difference step: truncation and round-off both ~1e-11 relative; the 1e-3 floor keeps the
// velocity step (1e-9 m/s) at the scale of v_eps.
constexpr double kJacobianStep = 1e-6;

void Rosenbrock4Stepper::Rhs::operator()(const UVector& x, UVector& dxdt, double) const {
  StateVector xs, ds;
  std::copy(x.begin(), x.end(), xs.begin());
  ++self->stats.rhs_evaluations;
  self->system_(xs, ds);
  std::copy(ds.begin(), ds.end(), dxdt.begin());
}

void Rosenbrock4Stepper::Jacobian::operator()(const UVector& x, UMatrix& jac, double, UVector& dfdt) const {
  StateVector xs, f_plus, f_minus, bound{};
  std::copy(x.begin(), x.end(), xs.begin());
  if (self->difference_steps_) self->difference_steps_(xs, bound);
  for (std::size_t j = 0; j < idx::size; ++j) {
    // Nothing depends on the position or the dissipated work; the model marks other zero columns (< 0).
    if (j == idx::x || j == idx::x + 1 || j == idx::w_diss || j == idx::psi || bound[j] < 0.0) {
      for (std::size_t i = 0; i < idx::size; ++i) jac(i, j) = 0.0;
      continue;
    }
    double h = kJacobianStep * std::max(std::abs(xs[j]), 1e-3);
    if (bound[j] > 0.0 && bound[j] < h) h = bound[j];
    const double saved = xs[j];
    xs[j] = saved + h;
    self->system_(xs, f_plus);
    xs[j] = saved - h;
    self->system_(xs, f_minus);
    self->stats.rhs_evaluations += 2;
    xs[j] = saved;
    for (std::size_t i = 0; i < idx::size; ++i) jac(i, j) = (f_plus[i] - f_minus[i]) / (2.0 * h);
  }
  for (std::size_t i = 0; i < idx::size; ++i) dfdt[i] = 0.0;  // autonomous
}

void Rosenbrock4Stepper::step(double) {
  const std::uint64_t tried = attempts_;
  current().do_step(std::make_pair(Rhs{this}, Jacobian{this}));
  stats.rejected += attempts_ - tried - 1;  // odeint retries a rejected step inside do_step()
  restarted_ = false;
  next_dt_ = current().current_time_step();
  StateVector y;
  std::copy(current().current_state().begin(), current().current_state().end(), y.begin());
  const double n2 = y[idx::f] * y[idx::f] + y[idx::f + 1] * y[idx::f + 1] + y[idx::f + 2] * y[idx::f + 2];
  renormalized_ = std::abs(n2 - 1.0) > 1e-10 && std::isfinite(n2);
  if (renormalized_) {
    // odeint's Rosenbrock stepper cannot be copied: continue in the twin, keep this one for interpolation.
    const double t = current().current_time();
    active_ = 1 - active_;
    normalize_figure_axis(y);
    std::copy(y.begin(), y.end(), x_.begin());
    current().initialize(x_, t, next_dt_);
  }
  copy_current();
  ++stats.steps;
}

void Rosenbrock4Stepper::state_at(double t, StateVector& y) const {
  if (t >= time() || restarted_) {
    y = current_;
    return;
  }
  interval().calc_state(t, scratch_);
  std::copy(scratch_.begin(), scratch_.end(), y.begin());
  normalize_figure_axis(y);
}

}  // namespace top_sim
