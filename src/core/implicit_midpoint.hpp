// The implicit midpoint rule y1 = y0 + h f((y0 + y1) / 2), solved by simplified Newton: the step of the fixed-step
// method `implicit_midpoint` (its time keeping is FixedStepper's, fixed_stepper.cpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "top_sim/integrators.hpp"

namespace top_sim {

// One-stage Gauss-Legendre: R(z) = (1 + z/2) / (1 - z/2), A-stable with |R(iy)| = 1, so an oscillation such as the
// top's nutation keeps its amplitude at any step (its frequency w becomes 2 atan(h w / 2) / h); order 2, symplectic.
// The unknown is K = y1 - y0; the inverse of I - h/2 J (J by forward differences) is kept over steps while the
// iteration contracts fast. No heap allocation per step.
//
// Fitted (method fitted_midpoint): K = h G f(y0 + K/2) with G = I + (g - 1) P, where w^2 = -tr(J^2) / 2 is the
// fastest oscillation's (the nutation's: every other eigenvalue of the top's J is ~100 times smaller),
// P = J^4 / w^4 its spectral projector (the slow eigenvalues' 4th powers vanish beside w^4), and
// g = tan(h w / 2) / (h w / 2). For y' = J y + b with constant J and b the step is then exact, the nutation's phase
// and amplitude included, at any h; between Jacobians, J is carried along the precession by rotating it about the
// plane normal by the change of the angular momentum's azimuth. What is left is the nonlinear coupling of the
// nutation into the slow motion, sampled once per step at the midpoint: near h w = 2 pi k it is sampled at the same
// phase every step and its error adds up (a resonance), at h w = pi (2 k + 1) the midpoint sits at the nutation's
// centre and the error is smallest. Without an oscillation (tr(J^2) >= 0) it is the plain rule.
class ImplicitMidpoint {
 public:
  using Vec = Eigen::Matrix<double, idx::size, 1>;
  using Mat = Eigen::Matrix<double, idx::size, idx::size>;

  explicit ImplicitMidpoint(DifferenceSteps difference_steps = {}, Azimuth azimuth = {}, bool fitted = false)
      : difference_steps_(std::move(difference_steps)), azimuth_of_(std::move(azimuth)), fitted_(fitted) {}

  // A new start (reset, event, mode switch): no previous K to predict from, a fresh Jacobian at the next step.
  void reset();
  // y <- y + K with K = h G f(y + K/2) (G = I unless fitted), each right-hand side counted in `rhs_count`. Throws
  // std::runtime_error naming t and h when Newton does not converge even with a fresh Jacobian; y is unchanged then.
  void step(const System& system, std::uint64_t& rhs_count, StateVector& y, double t, double h);

 private:
  enum class Outcome { converged, non_finite, diverged, too_many };
  struct Solver {
    const System& system;
    std::uint64_t& rhs_count;
  };

  void jacobian(const Solver& s, const StateVector& y);
  void factor(double h);
  void fit(double h);
  Vec predict(double h) const;
  Outcome newton(const Solver& s, const StateVector& y0, double h, Vec& k);
  Vec to_jacobian_frame(const Vec& v) const;
  Vec from_jacobian_frame(const Vec& v) const;
  const char* name() const { return fitted_ ? "fitted_midpoint" : "implicit_midpoint"; }
  std::string failure_message(Outcome outcome, double t, double h) const;

  DifferenceSteps difference_steps_;
  Azimuth azimuth_of_;
  bool fitted_ = false;
  Mat jac_ = Mat::Zero();
  Mat inverse_ = Mat::Identity();  // (I - 1/2 hG J)^-1
  Mat hg_ = Mat::Identity();       // h G (fitted only)
  double inverse_h_ = 0.0;         // its h (0: none)
  double w2_ = 0.0;                // the fastest oscillation's w^2 from J (fitted only; <= 0: none)
  double jac_azimuth_ = 0.0;       // the azimuth where J was evaluated
  double cos_turn_ = 1.0, sin_turn_ = 0.0;  // the turn about the normal since then (fitted only)
  bool refresh_ = true;      // evaluate J at the next step's start
  double eta_ = 1.0;         // the last step's theta / (1 - theta): the remaining error per increment
  Vec last_k_ = Vec::Zero();  // the last step's K and h
  double last_h_ = 0.0;
  bool has_last_ = false;     // no step since reset()
};

}  // namespace top_sim
