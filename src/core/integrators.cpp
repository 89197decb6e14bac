// Time steppers: Euler, RK4 and Rosenbrock 4 from Boost.Odeint; Dormand-Prince 5(4) as odeint computes it (its
// operations, our storage); semi-implicit Euler and the dopri5/rosenbrock4 switch here.
#include "top_sim/integrators.hpp"

#include "implicit_midpoint.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/ublas/matrix.hpp>
#include <boost/numeric/ublas/vector.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace top_sim {

namespace odeint = boost::numeric::odeint;

const char* to_string(Method m) {
  switch (m) {
    case Method::euler: return "euler";
    case Method::semi_implicit_euler: return "semi_implicit_euler";
    case Method::rk4: return "rk4";
    case Method::dopri5: return "dopri5";
    case Method::rosenbrock4: return "rosenbrock4";
    case Method::switching: return "switching";
    case Method::implicit_midpoint: return "implicit_midpoint";
    case Method::fitted_midpoint: return "fitted_midpoint";
  }
  return "?";
}

bool parse_method(const std::string& name, Method& out) {
  for (Method m : {Method::euler, Method::semi_implicit_euler, Method::rk4, Method::dopri5, Method::rosenbrock4,
                   Method::switching, Method::implicit_midpoint, Method::fitted_midpoint})
    if (name == to_string(m)) {
      out = m;
      return true;
    }
  return false;
}

bool is_adaptive(Method m) { return m == Method::dopri5 || m == Method::rosenbrock4 || m == Method::switching; }

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

// ---- fixed-step methods ---------------------------------------------------------------------------------

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

// ---- Dormand-Prince 5(4) with dense output ----------------------------------------------------------------

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

// The stages that live only inside one step (the trial state, k2, the error estimate): one set per thread, hot in
// the cache, instead of one per top (a thousand tops' steppers are the largest part of the node's memory per tick).
struct Dopri5Scratch {
  StateVector x_tmp{}, k2{}, x_err{};
};

Dopri5Scratch& dopri5_scratch() {
  static thread_local Dopri5Scratch scratch;
  return scratch;
}

// odeint's dense-output, controlled, first-same-as-last dopri5 (runge_kutta_dopri5 in dense_output_runge_kutta of
// controlled_runge_kutta) with the same operations in the same order through the same algebra, so the same bits;
// its per-top storage is what a step leaves for the next and for the dense output: the two states and derivatives
// (toggled), k3 to k6 (960 bytes, 15 cache lines; odeint's objects held 2032 bytes).
class Dopri5Stepper : public Stepper {
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

  void step(double) override {
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

  double time() const override { return t_; }
  // After reset() the last step's interval is kept (as odeint's initialize() keeps it): there is none to offer.
  double previous_time() const override { return restarted_ ? time() : t_old_; }
  const StateVector& state() const override { return x_[current_]; }
  double last_step_size() const override { return time() - previous_time(); }

  void state_at(double t, StateVector& y) const override {
    if (t >= time() || restarted_) {
      y = x_[current_];
      return;
    }
    interpolate(t, y);
    normalize_figure_axis(y);
  }

 private:
  static constexpr int kMaxTries = 500;

  void rhs(const StateVector& x, StateVector& dxdt) {
    ++stats.rhs_evaluations;
    system_(x, dxdt);
  }

  // controlled_runge_kutta::try_step (first same as last): writes the other state and derivative; on success
  // advances t_; either way dt_ is the next try's step.
  bool try_step(Dopri5Scratch& s) {
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
  void interpolate(double t, StateVector& y) const {
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
  void renormalize(StateVector& y, double n2) {
    normalize_figure_axis(y);
    const double n = std::sqrt(n2);  // normalize_figure_axis's norm
    for (std::size_t i = 0; i < 3; ++i) dxdt_[current_][idx::f + i] /= n;
  }

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

// ---- Rosenbrock 4 (stiff) with a finite-difference Jacobian ----------------------------------------------

using UVector = boost::numeric::ublas::vector<double>;
// Relative central-difference step: truncation and round-off both ~1e-11 relative; the 1e-3 floor keeps the
// velocity step (1e-9 m/s) at the scale of v_eps.
constexpr double kJacobianStep = 1e-6;
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

class Rosenbrock4Stepper : public Stepper {
  using Controller = odeint::rosenbrock4_controller<PhaseFreeRosenbrock4>;
  using Dense = odeint::rosenbrock4_dense_output<Controller>;

  struct Rhs {
    Rosenbrock4Stepper* self;
    void operator()(const UVector& x, UVector& dxdt, double) const {
      StateVector xs, ds;
      std::copy(x.begin(), x.end(), xs.begin());
      ++self->stats.rhs_evaluations;
      self->system_(xs, ds);
      std::copy(ds.begin(), ds.end(), dxdt.begin());
    }
  };
  // Central differences: Rosenbrock methods lose order with an inexact Jacobian, and forward differences at
  // 1e-9 relative (round-off ~1e-7) made 8x more steps on the default scene (docs/performance.md).
  struct Jacobian {
    Rosenbrock4Stepper* self;
    void operator()(const UVector& x, UMatrix& jac, double, UVector& dfdt) const {
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

  void step(double) override {
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

  double time() const override { return dense_[active_].current_time(); }
  // After reset() odeint keeps the last step's interval (initialize() does not clear it): there is none to offer.
  double previous_time() const override { return restarted_ ? time() : interval().previous_time(); }
  const StateVector& state() const override { return current_; }
  double last_step_size() const override { return time() - previous_time(); }
  double next_step_size() const { return next_dt_; }

  void state_at(double t, StateVector& y) const override {
    if (t >= time() || restarted_) {
      y = current_;
      return;
    }
    interval().calc_state(t, scratch_);
    std::copy(scratch_.begin(), scratch_.end(), y.begin());
    normalize_figure_axis(y);
  }

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

// ---- dopri5 / rosenbrock4 switch ---------------------------------------------------------------------------

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

// ---- the scene's method with rosenbrock4 across a stiff layer ------------------------------------------------

// The model says where the state sits in a known stiff layer (the slip-onset layer of physics.md section 9); there
// rosenbrock4 takes over from whatever method the scene chose, and hands back once the state has left the layer.
// The hand-over happens at the start of the next step, so dense output always comes from the stepper that made
// the last step.
class LayeredStepper : public Stepper {
 public:
  LayeredStepper(std::unique_ptr<Stepper> primary, std::unique_ptr<Stepper> layer, StiffLayer in_layer)
      : primary_(std::move(primary)), layer_(std::move(layer)), in_layer_(std::move(in_layer)) {}

  void reset(const StateVector& y, double t) override {
    layer_active_ = in_layer_(y, false);
    active().reset(y, t);
    switch_pending_ = false;
  }

  void step(double t_limit) override {
    if (switch_pending_) {
      const StateVector y = active().state();
      const double t = active().time();
      layer_active_ = !layer_active_;
      active().reset(y, t);
      switch_pending_ = false;
    }
    Stepper& a = active();
    const StepperStats before = a.stats;
    a.step(t_limit);
    stats.steps += a.stats.steps - before.steps;
    stats.rejected += a.stats.rejected - before.rejected;
    stats.rhs_evaluations += a.stats.rhs_evaluations - before.rhs_evaluations;
    if (layer_active_) layer_steps_ += a.stats.steps - before.steps;
    switch_pending_ = in_layer_(a.state(), layer_active_) != layer_active_;
  }

  double time() const override { return active().time(); }
  double previous_time() const override { return active().previous_time(); }
  const StateVector& state() const override { return active().state(); }
  void state_at(double t, StateVector& y) const override { active().state_at(t, y); }
  double last_step_size() const override { return active().last_step_size(); }
  std::uint64_t layer_steps() const override { return layer_steps_; }
  bool state_was_last_rhs() const override { return active().state_was_last_rhs(); }

 private:
  Stepper& active() { return layer_active_ ? *layer_ : *primary_; }
  const Stepper& active() const { return layer_active_ ? *layer_ : *primary_; }

  std::unique_ptr<Stepper> primary_, layer_;
  StiffLayer in_layer_;
  bool layer_active_ = false, switch_pending_ = false;
  std::uint64_t layer_steps_ = 0;
};

std::unique_ptr<Stepper> make_plain_stepper(const IntegratorSettings& settings, System system,
                                            DifferenceSteps difference_steps, Azimuth azimuth = {}) {
  switch (settings.method) {
    case Method::euler:
    case Method::semi_implicit_euler:
    case Method::rk4:
    case Method::implicit_midpoint:
    case Method::fitted_midpoint:
      return std::make_unique<FixedStepper>(settings.method, settings.dt, std::move(system),
                                            std::move(difference_steps), std::move(azimuth));
    case Method::dopri5:
      return std::make_unique<Dopri5Stepper>(settings, std::move(system));
    case Method::rosenbrock4:
      return std::make_unique<Rosenbrock4Stepper>(settings, std::move(system), std::move(difference_steps));
    case Method::switching:
      return std::make_unique<SwitchingStepper>(settings, std::move(system), std::move(difference_steps));
  }
  throw std::invalid_argument("make_stepper: unknown method");
}

}  // namespace

std::unique_ptr<Stepper> make_stepper(const IntegratorSettings& settings, System system,
                                      DifferenceSteps difference_steps, StiffLayer in_layer, Azimuth azimuth) {
  if (!in_layer || settings.method == Method::rosenbrock4)
    return make_plain_stepper(settings, std::move(system), std::move(difference_steps), std::move(azimuth));
  IntegratorSettings stiff = settings;
  stiff.method = Method::rosenbrock4;
  stiff.dt = kLayerFirstStep;
  return std::make_unique<LayeredStepper>(make_plain_stepper(settings, system, difference_steps, std::move(azimuth)),
                                          make_plain_stepper(stiff, system, difference_steps), std::move(in_layer));
}

}  // namespace top_sim
