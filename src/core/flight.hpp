// Flight in closed form (physics.md section 9, "Flight in closed form"): the centre of mass on a parabola, the
// torque-free gyrostat precessing regularly about its constant angular momentum, touchdown on the closed form.
#pragma once

#include <Eigen/Core>
#include <limits>

#include "top_sim/integrators.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// True where the flight has a closed form: the full model, gravity into the plane, and a rotor (if any) whose
// bearing decay rate is finite (rotor and shell both with axial inertia).
bool flight_in_closed_form(const Model& model);

// The constants of one flight, from the state at its start t0 (all in the plane frame P).
struct FlightMotion {
  double t0 = 0.0;
  StateVector y0{};
  Eigen::Vector3d r_cm = Eigen::Vector3d::Zero(), v_cm = Eigen::Vector3d::Zero();  // at t0
  Eigen::Vector3d l_hat = Eigen::Vector3d::UnitZ();  // direction of the angular momentum L (constant)
  Eigen::Vector3d L_over_Id = Eigen::Vector3d::Zero();  // L / I_d
  double rate = 0.0;          // precession rate |L| / I_d
  double body_rate = 0.0;     // sigma = omega . f_hat - L . f_hat / I_d at t0: spin about f_hat relative to the precession
  double axial = 0.0;         // L . f_hat (constant)
  // The bearing: nu = nu0 exp(-decay tau) hands the rotor's spin to the shell, sigma = body_rate + exchange (1 - exp).
  double decay = 0.0;         // c I_f / (J I_f') [1/s]; 0 without a rotor or bearing
  double exchange = 0.0;      // J nu0 / I_f [rad/s]: the rise of w_f once the rotor has stopped relative to the shell
  double f_along = 0.0;       // f_hat = f_along l_hat + f_perp cos(theta) + f_cross sin(theta), theta = rate (t - t0)
  Eigen::Vector3d f_perp = Eigen::Vector3d::Zero(), f_cross = Eigen::Vector3d::Zero();
  // 1 + f_z = D + rho cos(theta - delta): the spin phase integrates psi' in closed form over it.
  double D = 2.0, rho = 0.0, delta = 0.0, G0 = 0.0;
};

// The closed-form constants of the flight that starts in state y at time t.
FlightMotion flight_motion(const Model& model, const StateVector& y, double t);

// The state at time t (any t; the flight's own at t >= t0).
void flight_state(const Model& model, const FlightMotion& m, double t, StateVector& y);

// The gap and its rate alone at time t (what the touchdown search evaluates).
void flight_gap(const Model& model, const FlightMotion& m, double t, double& gap, double& gap_rate);

// The first time after t0 at which the gap is <= 0 while closing (the simulator's touchdown), located on the
// closed form to 1e-15 relative in t; infinity when the search finds none.
double touchdown_time(const Model& model, const FlightMotion& m);

// A Stepper whose steps are the closed form: one step to the touchdown or the limit; dense output exact.
class FlightStepper final : public Stepper {
 public:
  explicit FlightStepper(const Model& model) : model_(model) {}
  void reset(const StateVector& y, double t) override;
  void step(double t_limit) override;
  double time() const override { return t_; }
  double previous_time() const override { return t_previous_; }
  const StateVector& state() const override { return y_; }
  void state_at(double t, StateVector& y) const override { flight_state(model_, motion_, t, y); }
  double last_step_size() const override { return t_ - t_previous_; }
  // True when the last step ended at the touchdown.
  bool at_touchdown() const { return t_ == touchdown_; }
  double touchdown() const { return touchdown_; }

 private:
  const Model& model_;  // the simulator's, which changes only between resets
  FlightMotion motion_;
  StateVector y_{};
  double t_ = 0.0, t_previous_ = 0.0;
  double touchdown_ = std::numeric_limits<double>::infinity();
};

}  // namespace top_sim
