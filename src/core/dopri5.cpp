// Dormand-Prince 5(4): odeint's operations in odeint's order through a paired algebra (the same bits).
#include "dopri5.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace top_sim {

namespace {

// odeint's array_algebra for the state, with its linear combinations (scale_sumN, all dopri5 uses) made on two
// components per SSE2 operation: the same IEEE operations on each component (the same bits) in about half the
// instructions (odeint's loop stays scalar: it cannot rule out aliasing). Other operations run component-wise.
struct PairAlgebra {
  using Pair = double __attribute__((vector_size(16)));
  static constexpr std::size_t kN = idx::size;

  template <class A>
  static Pair load(const A& a, std::size_t i) {
    Pair p;
    std::memcpy(&p, &a[i], sizeof p);
    return p;
  }
  // out = op(in...): each pair of inputs is read before its output is written (odeint may pass out as an input).
  template <class Op, class Out, class... In>
  static void pairs(Op& op, Out& out, const In&... in) {
    std::size_t i = 0;
    for (; i + 2 <= kN; i += 2) {
      Pair r;
      op(r, load(in, i)...);
      std::memcpy(&out[i], &r, sizeof r);
    }
    for (; i < kN; ++i) op(out[i], in[i]...);
  }
  template <class Op, class... S>
  static void elements(Op& op, S&... s) {
    for (std::size_t i = 0; i < kN; ++i) op(s[i]...);
  }

  template <class S1, class S2, class Op>
  static void for_each2(S1& s1, S2& s2, Op op) { elements(op, s1, s2); }
  template <class S1, class S2, class S3, class Op>
  static void for_each3(S1& s1, S2& s2, S3& s3, Op op) { elements(op, s1, s2, s3); }
  template <class S1, class S2, class S3, class... F>
  static void for_each3(S1& s1, S2& s2, S3& s3, odeint::default_operations::scale_sum2<F...> op) {
    pairs(op, s1, s2, s3);
  }
  template <class S1, class S2, class S3, class S4, class Op>
  static void for_each4(S1& s1, S2& s2, S3& s3, S4& s4, Op op) { elements(op, s1, s2, s3, s4); }
  template <class S1, class S2, class S3, class S4, class... F>
  static void for_each4(S1& s1, S2& s2, S3& s3, S4& s4, odeint::default_operations::scale_sum3<F...> op) {
    pairs(op, s1, s2, s3, s4);
  }
  template <class S1, class S2, class S3, class S4, class S5, class Op>
  static void for_each5(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, Op op) { elements(op, s1, s2, s3, s4, s5); }
  template <class S1, class S2, class S3, class S4, class S5, class... F>
  static void for_each5(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, odeint::default_operations::scale_sum4<F...> op) {
    pairs(op, s1, s2, s3, s4, s5);
  }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class Op>
  static void for_each6(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, Op op) { elements(op, s1, s2, s3, s4, s5, s6); }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class... F>
  static void for_each6(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6,
                        odeint::default_operations::scale_sum5<F...> op) {
    pairs(op, s1, s2, s3, s4, s5, s6);
  }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class S7, class Op>
  static void for_each7(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, S7& s7,
                        Op op) { elements(op, s1, s2, s3, s4, s5, s6, s7); }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class S7, class... F>
  static void for_each7(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, S7& s7,
                        odeint::default_operations::scale_sum6<F...> op) {
    pairs(op, s1, s2, s3, s4, s5, s6, s7);
  }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class S7, class S8, class Op>
  static void for_each8(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, S7& s7, S8& s8,
                        Op op) { elements(op, s1, s2, s3, s4, s5, s6, s7, s8); }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class S7, class S8, class... F>
  static void for_each8(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, S7& s7, S8& s8,
                        odeint::default_operations::scale_sum7<F...> op) {
    pairs(op, s1, s2, s3, s4, s5, s6, s7, s8);
  }
};

}  // namespace

// The stages that live only inside one step (the trial state, k2, the error estimate): one set per thread, hot in
// the cache, instead of one per top (a thousand tops' steppers are the largest part of the node's memory per tick).
struct Dopri5Scratch {
  StateVector x_tmp{}, k2{}, x_err{};
};

namespace {

Dopri5Scratch& dopri5_scratch() {
  static thread_local Dopri5Scratch scratch;
  return scratch;
}

}  // namespace

void Dopri5Stepper::step(double) {
  if (!derivative_ready_) {
    rhs(x_[current_], dxdt_[current_]);
    derivative_ready_ = true;
  }
  Dopri5Scratch& scratch = dopri5_scratch();
  t_old_ = t_;
  for (int tries = 0;; ++tries) {
    const bool accepted = try_step(scratch);
    if (tries >= kMaxTries)  // odeint's failed_step_checker: its error, its message
      throw odeint::step_adjustment_error("Max number of iterations exceeded (" + std::to_string(kMaxTries) +
                                          "). A new step size was not found.");
    if (accepted) break;
  }
  current_ ^= 1;
  restarted_ = false;
  next_dt_ = dt_;
  StateVector& y = x_[current_];
  const double n2 = y[idx::f] * y[idx::f] + y[idx::f + 1] * y[idx::f + 1] + y[idx::f + 2] * y[idx::f + 2];
  renormalized_ = std::abs(n2 - 1.0) > 1e-10 && std::isfinite(n2);  // only when f_hat has drifted
  if (renormalized_) renormalize(y, n2);
  ++stats.steps;
}

void Dopri5Stepper::state_at(double t, StateVector& y) const {
  if (t >= time() || restarted_) {
    y = x_[current_];
    return;
  }
  interpolate(t, y);
  normalize_figure_axis(y);
}

// controlled_runge_kutta::try_step (first same as last): writes the other state and derivative; on success
// advances t_; either way dt_ is the next try's step.
bool Dopri5Stepper::try_step(Dopri5Scratch& s) {
  if (!adjuster_.check_step_size_limit(dt_)) {
    dt_ = adjuster_.get_max_dt();
    return false;
  }
  const double dt = dt_;
  constexpr double b21 = 1.0 / 5.0;
  constexpr double b31 = 3.0 / 40.0, b32 = 9.0 / 40.0;
  constexpr double b41 = 44.0 / 45.0, b42 = -56.0 / 15.0, b43 = 32.0 / 9.0;
  constexpr double b51 = 19372.0 / 6561.0, b52 = -25360.0 / 2187.0, b53 = 64448.0 / 6561.0, b54 = -212.0 / 729.0;
  constexpr double b61 = 9017.0 / 3168.0, b62 = -355.0 / 33.0, b63 = 46732.0 / 5247.0, b64 = 49.0 / 176.0,
                   b65 = -5103.0 / 18656.0;
  const StateVector& x = x_[current_];
  const StateVector& k1 = dxdt_[current_];
  StateVector& out = x_[current_ ^ 1];
  StateVector& k7 = dxdt_[current_ ^ 1];
  PairAlgebra::for_each3(s.x_tmp, x, k1, Ops::scale_sum2<double, double>(1.0, dt * b21));
  rhs(s.x_tmp, s.k2);
  PairAlgebra::for_each4(s.x_tmp, x, k1, s.k2, Ops::scale_sum3<double, double, double>(1.0, dt * b31, dt * b32));
  rhs(s.x_tmp, k3_);
  PairAlgebra::for_each5(s.x_tmp, x, k1, s.k2, k3_,
                         Ops::scale_sum4<double, double, double, double>(1.0, dt * b41, dt * b42, dt * b43));
  rhs(s.x_tmp, k4_);
  PairAlgebra::for_each6(
      s.x_tmp, x, k1, s.k2, k3_, k4_,
      Ops::scale_sum5<double, double, double, double, double>(1.0, dt * b51, dt * b52, dt * b53, dt * b54));
  rhs(s.x_tmp, k5_);
  PairAlgebra::for_each7(s.x_tmp, x, k1, s.k2, k3_, k4_, k5_,
                         Ops::scale_sum6<double, double, double, double, double, double>(
                             1.0, dt * b61, dt * b62, dt * b63, dt * b64, dt * b65));
  rhs(s.x_tmp, k6_);
  PairAlgebra::for_each7(out, x, k1, k3_, k4_, k5_, k6_,
                         Ops::scale_sum6<double, double, double, double, double, double>(
                             1.0, dt * kC1, dt * kC3, dt * kC4, dt * kC5, dt * kC6));
  rhs(out, k7);
  const double dc1 = kC1 - 5179.0 / 57600.0, dc3 = kC3 - 7571.0 / 16695.0, dc4 = kC4 - 393.0 / 640.0,
               dc5 = kC5 - -92097.0 / 339200.0, dc6 = kC6 - 187.0 / 2100.0, dc7 = -1.0 / 40.0;
  PairAlgebra::for_each7(s.x_err, k1, k3_, k4_, k5_, k6_, k7,
                         Ops::scale_sum6<double, double, double, double, double, double>(
                             dt * dc1, dt * dc3, dt * dc4, dt * dc5, dt * dc6, dt * dc7));
  PairAlgebra algebra;
  const double error = checker_.error(algebra, x, k1, s.x_err, dt);
  if (error > 1.0) {
    dt_ = adjuster_.decrease_step(dt, error, 4);
    return false;
  }
  t_ += dt;
  dt_ = adjuster_.increase_step(dt, error, 5);
  return true;
}

// runge_kutta_dopri5::calc_state: the continuous extension over the last step.
void Dopri5Stepper::interpolate(double t, StateVector& y) const {
  const double dt = t_ - t_old_;
  const double theta = (t - t_old_) / dt;
  const double X1 = 5.0 * (2558722523.0 - 31403016.0 * theta) / 11282082432.0;
  const double X3 = 100.0 * (882725551.0 - 15701508.0 * theta) / 32700410799.0;
  const double X4 = 25.0 * (443332067.0 - 31403016.0 * theta) / 1880347072.0;
  const double X5 = 32805.0 * (23143187.0 - 3489224.0 * theta) / 199316789632.0;
  const double X6 = 55.0 * (29972135.0 - 7076736.0 * theta) / 822651844.0;
  const double X7 = 10.0 * (7414447.0 - 829305.0 * theta) / 29380423.0;
  const double theta_m_1 = theta - 1.0;
  const double theta_sq = theta * theta;
  const double A = theta_sq * (3.0 - 2.0 * theta);
  const double B = theta_sq * theta_m_1;
  const double C = theta_sq * theta_m_1 * theta_m_1;
  const double D = theta * theta_m_1 * theta_m_1;
  const double b1 = A * kC1 - C * X1 + D, b3 = A * kC3 + C * X3, b4 = A * kC4 - C * X4, b5 = A * kC5 + C * X5,
               b6 = A * kC6 - C * X6, b7 = B + C * X7;
  const int old = current_ ^ 1;
  PairAlgebra::for_each8(y, x_[old], dxdt_[old], k3_, k4_, k5_, k6_, dxdt_[current_],
                         Ops::scale_sum7<double, double, double, double, double, double, double>(
                             1.0, dt * b1, dt * b3, dt * b4, dt * b5, dt * b6, dt * b7));
}

// f_hat back to unit length in place, and the first-same-as-last derivative with it (no re-initialisation): only
// f' = omega x f reads |f| (the model reads f_hat normalised) and it is linear in f, so f' / |f| is what the
// re-evaluation would give, to rounding; the last step's interpolant at its end (theta = 1) does not read it.
void Dopri5Stepper::renormalize(StateVector& y, double n2) {
  normalize_figure_axis(y);
  const double n = std::sqrt(n2);  // normalize_figure_axis's norm
  for (std::size_t i = 0; i < 3; ++i) dxdt_[current_][idx::f + i] /= n;
}

}  // namespace top_sim
