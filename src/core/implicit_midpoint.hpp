// The implicit midpoint rule y1 = y0 + h f((y0 + y1) / 2), solved by simplified Newton: the step of the fixed-step
// method `implicit_midpoint` (its time keeping is FixedStepper's, integrators.cpp).
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
class ImplicitMidpoint {
 public:
  using Vec = Eigen::Matrix<double, idx::size, 1>;
  using Mat = Eigen::Matrix<double, idx::size, idx::size>;

  explicit ImplicitMidpoint(DifferenceSteps difference_steps = {}) : difference_steps_(std::move(difference_steps)) {}

  // A new start (reset, event, mode switch): no previous K to predict from, a fresh Jacobian at the next step.
  void reset();
  // y <- y + K with K = h f(y + K/2), each right-hand side counted in `rhs_count`. Throws std::runtime_error naming
  // t and h when Newton does not converge even with a fresh Jacobian; y is unchanged then.
  void step(const System& system, std::uint64_t& rhs_count, StateVector& y, double t, double h);

 private:
  enum class Outcome { converged, non_finite, diverged, too_many };
  struct Solver {
    const System& system;
    std::uint64_t& rhs_count;
  };

  void jacobian(const Solver& s, const StateVector& y);
  void factor(double h);
  Vec predict(double h) const;
  Outcome newton(const Solver& s, const StateVector& y0, double h, Vec& k);
  static std::string failure_message(Outcome outcome, double t, double h);

  DifferenceSteps difference_steps_;
  Mat jac_ = Mat::Zero();
  Mat inverse_ = Mat::Identity();  // (I - h/2 J)^-1
  double inverse_h_ = 0.0;         // its h (0: none)
  bool refresh_ = true;      // evaluate J at the next step's start
  double eta_ = 1.0;         // the last step's theta / (1 - theta): the remaining error per increment
  Vec last_k_ = Vec::Zero();  // the last step's K and h
  double last_h_ = 0.0;
  bool has_last_ = false;     // no step since reset()
};

}  // namespace top_sim
