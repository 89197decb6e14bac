// Time steppers over the state vector (Boost.Odeint where it has the method).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "top_sim/limits.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// switching: dopri5 while the motion is non-stiff, rosenbrock4 once its steps buy more simulated time per cost
// (the sleeping regime, where explicit steps are stability-limited). implicit_midpoint: fixed step, A-stable with
// |R(iy)| = 1 (an oscillation keeps its amplitude at any step), order 2. fitted_midpoint: implicit midpoint fitted to
// the fastest oscillation of the Jacobian (the nutation), which it then carries exactly (phase and amplitude) at steps
// longer than its period; see implicit_midpoint.hpp for where it works.
enum class Method { euler, semi_implicit_euler, rk4, dopri5, rosenbrock4, switching, implicit_midpoint, fitted_midpoint };

const char* to_string(Method m);
bool parse_method(const std::string& name, Method& out);
bool is_adaptive(Method m);

struct IntegratorSettings {
  Method method = Method::dopri5;
  double dt = 1.0e-4;   // fixed step; first step of adaptive methods [s]
  double rtol = 1.0e-8;
  double atol = 1.0e-10;
  double max_dt = 0.0;  // upper bound on adaptive steps [s]; 0 = none
  // The run stops with a numerical fault when the relative energy-balance residual exceeds this (inf = never).
  double max_energy_residual = kDefaultMaxEnergyResidual;
};

using System = std::function<void(const StateVector&, StateVector&)>;

struct StepperStats {
  std::uint64_t steps = 0;
  std::uint64_t rejected = 0;
  std::uint64_t rhs_evaluations = 0;
};

// A stepper owns its current state; the state between its last two steps is available (dense output).
class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual void reset(const StateVector& y, double t) = 0;
  // One accepted step; fixed-step methods do not pass t_limit, adaptive ones may (then interpolate).
  virtual void step(double t_limit) = 0;
  virtual double time() const = 0;
  virtual double previous_time() const = 0;
  virtual const StateVector& state() const = 0;
  // State at t in [previous_time(), time()].
  virtual void state_at(double t, StateVector& y) const = 0;
  virtual double last_step_size() const = 0;
  // Steps made by rosenbrock4 inside a stiff layer (see StiffLayer below); 0 for plain steppers.
  virtual std::uint64_t layer_steps() const { return 0; }
  // True when the last call of the system was at state() itself, bit for bit (dopri5's first-same-as-last stage,
  // no renormalisation since): what that call computed at the state can be reused.
  virtual bool state_was_last_rhs() const { return false; }
  StepperStats stats;
};

// Upper bounds on the finite-difference steps of an approximate Jacobian (0 = no bound, < 0 = zero column):
// a regularised friction kink of width v_eps must not be stepped across.
using DifferenceSteps = std::function<void(const StateVector& y, StateVector& max_step)>;

// The azimuth about the plane normal of a direction that turns with the state's slow rotation and not with its fast
// one (the top's angular momentum) [rad]: fitted_midpoint carries its Jacobian along it by the model's symmetry about
// the normal.
using Azimuth = std::function<double(const StateVector& y)>;

// True where the state lies in a stiff layer that rosenbrock4 must cross, whatever the scene's method (physics.md
// section 9: slip onset). `inside` says whether the state was in the layer at the last check (for hysteresis).
using StiffLayer = std::function<bool(const StateVector& y, bool inside)>;

// First rosenbrock4 step on entering a stiff layer [s]: the layer's time scale is v_eps / (mu g) ~ 1e-10 s, and
// the controller grows the step 5x per accepted step.
constexpr double kLayerFirstStep = 1.0e-9;

// `system` is called for every right-hand side; the stepper counts the calls. dopri5 renormalises f_hat in place
// and scales the first-same-as-last f' by 1/|f|: the system must read f only as f_hat, but for f' linear in f. With `in_layer`, steps inside the
// stiff layer are made by rosenbrock4 (the scene's rtol and atol).
std::unique_ptr<Stepper> make_stepper(const IntegratorSettings& settings, System system,
                                      DifferenceSteps difference_steps = {}, StiffLayer in_layer = {},
                                      Azimuth azimuth = {});

}  // namespace top_sim
