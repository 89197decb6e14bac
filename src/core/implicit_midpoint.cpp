// The implicit midpoint step (plain or fitted to the nutation): simplified Newton on K = y1 - y0 with a kept inverse
// of I - 1/2 hG J.
#include "implicit_midpoint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace top_sim {

namespace {

// Converged when the estimated remaining error is below this relative to max(|y_i|, 1) (omega: max(|omega|, 1)) in
// every component. The contact-point error hardly sees it (1e-10 to 1e-13 give the same to 3 digits on the
// frictionless top at dt 1 to 30 ms; 1e-8 moves the kept nutation by 1 % at 1 ms), the energy does: on the level
// frictionless top at dt 5 ms the energy error over 5 s is 1.8e-9 at 1e-10, 1.4e-10 at 1e-11, 5.0e-11 at 1e-12 and at
// 1e-13 (there the method's own, without drift). 1e-12 costs 0.5 to 1.5 more iterations a step than 1e-10.
constexpr double kTolerance = 1e-12;
constexpr double kDiverging = 0.5;     // a contraction rate from which the iteration is given up
// A converged step that contracted slower refreshes J for the next step: the top's precession turns J by ~0.01 of
// its norm per 5 ms step; 0.01 to 0.3 were tried on the frictionless top, 0.03 made the fewest right-hand sides.
constexpr double kRefreshRate = 0.03;
constexpr int kMaxIterations = 10;
const double kColumnStep = std::sqrt(std::numeric_limits<double>::epsilon());
constexpr double kColumnScale = 1e-3;  // the floor of |y_j| in the column step [state units]

// Nothing depends on the position, the dissipated work or the spin phase (their columns are zero).
bool constant_column(std::size_t j) { return j == idx::x || j == idx::x + 1 || j == idx::w_diss || j == idx::psi; }

ImplicitMidpoint::Vec as_vec(const StateVector& y) { return Eigen::Map<const ImplicitMidpoint::Vec>(y.data()); }

using Augmented = Eigen::Matrix<double, idx::size, 2 * idx::size, Eigen::RowMajor>;

// Gauss-Jordan elimination with partial pivoting on [A | I], rows contiguous: Eigen's inverse() of a 15x15 LU goes
// through its blocked general paths. False when A is singular.
bool invert(const ImplicitMidpoint::Mat& a, ImplicitMidpoint::Mat& out) {
  Augmented m;
  m.leftCols<idx::size>() = a;
  m.rightCols<idx::size>().setIdentity();
  for (int k = 0; k < static_cast<int>(idx::size); ++k) {
    int p = k;
    for (int i = k + 1; i < static_cast<int>(idx::size); ++i)
      if (std::abs(m(i, k)) > std::abs(m(p, k))) p = i;
    if (m(p, k) == 0.0) return false;
    if (p != k) m.row(p).swap(m.row(k));
    m.row(k) *= 1.0 / m(k, k);
    for (int i = 0; i < static_cast<int>(idx::size); ++i)
      if (i != k && m(i, k) != 0.0) m.row(i) -= m(i, k) * m.row(k);
  }
  out = m.rightCols<idx::size>();
  return true;
}

// A x with plain loops over the columns (Eigen's general matrix-vector product takes its generic path at 15x15).
ImplicitMidpoint::Vec times(const ImplicitMidpoint::Mat& a, const ImplicitMidpoint::Vec& x) {
  ImplicitMidpoint::Vec y = a.col(0) * x[0];
  for (int j = 1; j < static_cast<int>(idx::size); ++j) y += a.col(j) * x[j];
  return y;
}

// The in-plane pairs that turn with a rotation about the plane normal (z): position, velocity, f_hat, omega.
constexpr std::size_t kTurning[] = {idx::x, idx::u, idx::f, idx::omega};

// v turned about the normal by the angle whose cosine and sine are c and s.
ImplicitMidpoint::Vec turned(const ImplicitMidpoint::Vec& v, double c, double s) {
  ImplicitMidpoint::Vec r = v;
  for (std::size_t i : kTurning) {
    r[i] = c * v[i] - s * v[i + 1];
    r[i + 1] = s * v[i] + c * v[i + 1];
  }
  return r;
}

}  // namespace

// The model is symmetric about the plane normal (gravity's in-plane part is a constant, which J does not see):
// J(Q y) = Q J(y) Q^T for a turn Q about it. The kept J is used in its own frame, vectors turned into it and back.
ImplicitMidpoint::Vec ImplicitMidpoint::to_jacobian_frame(const Vec& v) const {
  return fitted_ ? turned(v, cos_turn_, -sin_turn_) : v;
}

ImplicitMidpoint::Vec ImplicitMidpoint::from_jacobian_frame(const Vec& v) const {
  return fitted_ ? turned(v, cos_turn_, sin_turn_) : v;
}

void ImplicitMidpoint::reset() {
  refresh_ = true;
  has_last_ = false;
  eta_ = 1.0;
}

void ImplicitMidpoint::jacobian(const Solver& s, const StateVector& y) {
  StateVector f0, f1, bound{}, yj = y;
  s.system(y, f0);
  ++s.rhs_count;
  if (difference_steps_) difference_steps_(y, bound);
  for (std::size_t j = 0; j < idx::size; ++j) {
    jac_.col(j).setZero();
    if (constant_column(j) || bound[j] < 0.0) continue;
    double d = kColumnStep * std::max(std::abs(y[j]), kColumnScale);
    if (bound[j] > 0.0 && bound[j] < d) d = bound[j];
    yj[j] = y[j] + d;
    d = yj[j] - y[j];  // the step actually taken (rounding)
    s.system(yj, f1);
    ++s.rhs_count;
    yj[j] = y[j];
    for (std::size_t i = 0; i < idx::size; ++i) jac_(i, j) = (f1[i] - f0[i]) / d;
  }
  refresh_ = false;
  inverse_h_ = 0.0;
  if (!fitted_) return;
  w2_ = -0.5 * jac_.cwiseProduct(jac_.transpose()).sum();  // -tr(J^2) / 2: the fast pair's +-i w dominate it
  jac_azimuth_ = azimuth_of_ ? azimuth_of_(y) : 0.0;
}

// The inverse itself: a solve is then one matrix-vector product (two triangular solves of an LU are sequential).
void ImplicitMidpoint::factor(double h) {
  if (fitted_) fit(h);
  const Mat m = fitted_ ? Mat(Mat::Identity() - 0.5 * hg_ * jac_) : Mat(Mat::Identity() - 0.5 * h * jac_);
  // A singular matrix leaves NaN: the iteration reports a non-finite increment, the step its fault.
  if (!invert(m, inverse_))
    inverse_.setConstant(std::numeric_limits<double>::quiet_NaN());
  inverse_h_ = h;
}

// h G = h (I + (g - 1) J^4 / w^4), g = tan(h w / 2) / (h w / 2): the midpoint rule's phase 2 atan(g h w / 2) is then
// h w for the nutation, and G is I to (slow rate / w)^4 for the rest.
void ImplicitMidpoint::fit(double h) {
  hg_ = h * Mat::Identity();
  if (!(w2_ > 0.0 && std::isfinite(w2_))) return;  // no oscillation: the plain rule
  const Mat j2 = jac_ * jac_;
  const double half = 0.5 * h * std::sqrt(w2_), g = std::tan(half) / half;
  hg_.noalias() += (h * (g - 1.0) / (w2_ * w2_)) * (j2 * j2);
}

// The first guess of K. After a step of the same h: that step's K carried on by the midpoint rule's own linear map
// R = (I - h/2 J)^-1 (I + h/2 J) = 2 (I - h/2 J)^-1 - I (fitted: hG in place of h, in the kept J's frame), exact
// for the linearised nutation, which extrapolating the slopes in time would amplify (by 4 sin^2(h w / 2) = 2.1 at
// h w = 1.6, linearly); one iteration fewer per step on the frictionless top. After a step of another h: that K scaled; after a reset: 0. It reads step sizes only, not
// times: a run sampled at step ends predicts the same bits.
ImplicitMidpoint::Vec ImplicitMidpoint::predict(double h) const {
  if (!has_last_) return Vec::Zero();
  if (last_h_ != h) return (h / last_h_) * last_k_;
  const Vec k = to_jacobian_frame(last_k_);
  return from_jacobian_frame(2.0 * times(inverse_, k) - k);
}

// Simplified Newton on K - h f(y0 + K/2) = 0; stops when theta / (1 - theta) times the last increment (Hairer &
// Wanner, Solving ODEs II, section IV.8) is below the tolerance, theta from this step or, at its first increment,
// the last step's.
ImplicitMidpoint::Outcome ImplicitMidpoint::newton(const Solver& s, const StateVector& y0, double h, Vec& k) {
  Vec scale;
  for (std::size_t i = 0; i < idx::size; ++i) scale[i] = kTolerance * std::max(std::abs(y0[i]), 1.0);
  const double spin_scale = kTolerance * std::max(angular_velocity(y0).norm(), 1.0);  // omega's components alike
  for (std::size_t i = idx::omega; i < idx::omega + 3; ++i) scale[i] = spin_scale;
  double eta = std::pow(std::max(eta_, std::numeric_limits<double>::epsilon()), 0.8), last = 0.0, theta = 0.0;
  StateVector z, fz;
  for (int it = 0; it < kMaxIterations; ++it) {
    for (std::size_t i = 0; i < idx::size; ++i) z[i] = y0[i] + 0.5 * k[i];
    s.system(z, fz);
    ++s.rhs_count;
    const Vec dk = fitted_ ? from_jacobian_frame(times(inverse_, times(hg_, to_jacobian_frame(as_vec(fz))) -
                                                             to_jacobian_frame(k)))
                           : Vec(times(inverse_, h * as_vec(fz) - k));
    if (!dk.allFinite()) return Outcome::non_finite;
    k += dk;
    const double norm = dk.cwiseAbs().cwiseQuotient(scale).maxCoeff();
    if (it > 0) {
      theta = norm / last;
      if (!(theta < kDiverging)) return Outcome::diverged;
      eta = theta / (1.0 - theta);
    }
    if (eta * norm <= 1.0 || norm == 0.0) {
      eta_ = eta;
      if (theta > kRefreshRate) refresh_ = true;
      return Outcome::converged;
    }
    last = norm;
  }
  return Outcome::too_many;
}

// Tries the kept J with the predictor; failing, a fresh J with the predictor (if J was not fresh), then from K = 0.
void ImplicitMidpoint::step(const System& system, std::uint64_t& rhs_count, StateVector& y, double t, double h) {
  const Solver s{system, rhs_count};
  Outcome outcome = Outcome::too_many;
  bool fresh = false, from_zero = false;
  for (int attempt = 0; attempt < 3 && !from_zero; ++attempt) {
    const bool refresh = refresh_ || (attempt > 0 && !fresh);
    if (refresh) jacobian(s, y);
    if (fitted_ && azimuth_of_) {
      const double turn = azimuth_of_(y) - jac_azimuth_;
      cos_turn_ = std::cos(turn);
      sin_turn_ = std::sin(turn);
    }
    fresh = fresh || refresh;
    if (inverse_h_ != h) factor(h);
    from_zero = attempt > 0 && !refresh;
    Vec k = from_zero ? Vec::Zero() : predict(h);
    outcome = newton(s, y, h, k);
    if (outcome == Outcome::converged) {
      for (std::size_t i = 0; i < idx::size; ++i) y[i] += k[i];
      last_k_ = k;
      last_h_ = h;
      has_last_ = true;
      return;
    }
    eta_ = 1.0;
  }
  throw std::runtime_error(failure_message(outcome, t, h));
}

std::string ImplicitMidpoint::failure_message(Outcome outcome, double t, double h) const {
  std::ostringstream os;
  os.precision(17);
  os << name() << ": the Newton iteration failed at t = " << t << " s with h = " << h << " s ("
     << (outcome == Outcome::non_finite ? "a non-finite rate"
         : outcome == Outcome::diverged ? "it diverged"
                                        : "no convergence in " + std::to_string(kMaxIterations) + " iterations")
     << ", also with a fresh Jacobian)";
  return os.str();
}

}  // namespace top_sim
