// The Simulator: time, stepper, events, commands, fault location (physics.md sections 4 and 8).
#include "top_sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "top_sim/adiabatic.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/orientation.hpp"

namespace top_sim {

namespace {

ContactMargins margins_of(const Model& model, const StateVector& y) {
  Dynamics dyn;
  evaluate_dynamics(model, y, dyn);
  return dyn.margins;
}

double shell_spin(const StateVector& y) { return angular_velocity(y).dot(figure_axis(y).normalized()); }

}  // namespace

Simulator::Simulator(const Scene& scene) : scene_(scene), model_(scene.model) {
  stepper_ = make_stepper(
      scene_.integrator, [this](const StateVector& y, StateVector& dydt) { model_derivative(model_, y, dydt); },
      [this](const StateVector& y, StateVector& h) { jacobian_difference_steps(model_, y, h); });
  reset();
}

void Simulator::reset() {
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.clear();
  }
  model_ = scene_.model;
  y_ = initial_state(scene_);
  t_origin_ = t_;
  next_event_ = 0;
  fault_ = ContactFault::none;
  fault_message_.clear();
  max_residual_ = 0.0;
  regime_ = Regime::nutating;
  restart_stepper();
  update_regime();
}

// After any jump of the state or the model: re-base the energy balance and check the new state for faults.
void Simulator::restart_stepper() {
  if (model_.kind == ModelKind::adiabatic) project_to_stationary(model_, y_);
  balance_.rebase(model_, y_);
  stepper_->reset(y_, t_);
  last_margins_ = margins_of(model_, y_);
  const ContactFault f = all_finite(y_) ? fault_of(last_margins_) : ContactFault::numerical;
  if (f != ContactFault::none && model_.kind == ModelKind::full) {
    fault_ = f;
    fault_message_ = describe(f, last_margins_, t_);
  }
}

std::string Simulator::submit(const Command& command) {
  const std::string error = validate(command, model_);
  if (!error.empty()) return error;
  std::lock_guard<std::mutex> lock(pending_mutex_);
  pending_.push_back(command);
  return "";
}

void Simulator::apply_now(const Command& c) {
  const Eigen::Vector3d f_hat = figure_axis(y_).normalized();
  const double spin = shell_spin(y_);
  const double rotor_spin = spin + y_[idx::nu];
  if (c.inclination) model_.plane = make_plane(*c.inclination, model_.plane.gravity);
  if (c.friction) model_.friction = *c.friction;
  if (c.rotor_coupling) model_.top.rotor.coupling = *c.rotor_coupling;
  if (c.spin) {
    set_angular_velocity(y_, angular_velocity(y_) + (*c.spin - spin) * f_hat);
    if (model_.top.has_rotor) y_[idx::nu] = rotor_spin - *c.spin;  // the rotor keeps its absolute spin
  }
  if (c.rotor_spin) y_[idx::nu] = *c.rotor_spin - shell_spin(y_);
}

void Simulator::apply_pending() {
  std::vector<Command> due;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    due.swap(pending_);
  }
  while (next_event_ < scene_.events.size() && t_origin_ + scene_.events[next_event_].t <= t_)
    due.push_back(scene_.events[next_event_++].command);
  if (due.empty()) return;
  for (const Command& c : due) apply_now(c);
  restart_stepper();
}

void Simulator::advance_to(double t_target) {
  while (fault_ == ContactFault::none && t_ < t_target) {
    apply_pending();
    if (fault_ != ContactFault::none) return;
    double t_stop = t_target;
    if (next_event_ < scene_.events.size()) t_stop = std::min(t_stop, t_origin_ + scene_.events[next_event_].t);
    try {
      while (stepper_->time() < t_stop) {
        stepper_->step(t_stop);
        if (!check_last_step()) return;
      }
    } catch (const std::exception& e) {  // odeint gives up when it cannot find an acceptable step
      fault_ = ContactFault::numerical;
      fault_message_ = describe(fault_, last_margins_, stepper_->time()) + " (" + e.what() + ")";
      return;
    }
    stepper_->state_at(t_stop, y_);
    t_ = t_stop;
  }
  apply_pending();  // events due exactly at t_target take effect now, so the state shows them
  update_regime();
}

void Simulator::update_regime() {
  if (fault_ != ContactFault::none) {
    regime_ = Regime::contact_fault;
    return;
  }
  Dynamics dyn;
  evaluate_dynamics(model_, y_, dyn);
  const RegimeIndicators ind = model_.kind == ModelKind::adiabatic ? RegimeIndicators{} : regime_indicators(model_, y_, dyn);
  regime_ = classify(model_.regime, ind, false, regime_);
}

// Checks the accepted step for faults; on one, moves the state to the located fault instant.
bool Simulator::check_last_step() {
  const StateVector& y = stepper_->state();
  if (!all_finite(y)) {
    fault_ = ContactFault::numerical;
    t_ = stepper_->previous_time();
    stepper_->state_at(t_, y_);
    fault_message_ = describe(fault_, last_margins_, t_);
    return false;
  }
  max_residual_ = std::max(max_residual_, balance_.residual(model_, y));
  if (model_.kind != ModelKind::full) return true;
  const ContactMargins m = margins_of(model_, y);
  if (fault_of(m) == ContactFault::none) {
    last_margins_ = m;
    return true;
  }
  // Bisect on the dense output for the first instant any margin changes sign.
  double lo = stepper_->previous_time(), hi = stepper_->time();
  StateVector ym;
  for (int i = 0; i < 60 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    stepper_->state_at(mid, ym);
    if (fault_of(margins_of(model_, ym)) == ContactFault::none)
      lo = mid;
    else
      hi = mid;
  }
  stepper_->state_at(hi, y_);
  t_ = hi;
  last_margins_ = margins_of(model_, y_);
  fault_ = fault_of(last_margins_);
  if (fault_ == ContactFault::none) fault_ = fault_of(m);
  fault_message_ = describe(fault_, last_margins_, t_);
  return false;
}

StationaryState Simulator::stationary() const { return stationary_state(model_, shell_spin(y_)); }

Snapshot Simulator::snapshot() const {
  Snapshot s = make_snapshot(model_, y_, t_, balance_, stationary(), regime_);
  s.regime = regime_;  // classified once, at the end of the last advance (with its hysteresis)
  if (fault_ != ContactFault::none) {
    s.fault = fault_;
    s.fault_message = fault_message_;
    s.regime = Regime::contact_fault;
  }
  return s;
}

Snapshot make_snapshot(const Model& model, const StateVector& y, double t, const EnergyBalance& balance,
                       const StationaryState& stationary, Regime previous) {
  Snapshot s;
  Dynamics dyn;
  evaluate_dynamics(model, y, dyn);
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d u = velocity3(y);
  s.t = t;
  s.alpha = model.plane.inclination;
  s.tip_center = Eigen::Vector3d(y[idx::x], y[idx::x + 1], top.tip_radius);
  s.com = s.tip_center + top.com_offset * f_hat;
  s.orientation = body_orientation(f_hat, y[idx::psi]);
  s.tip_velocity = u;
  s.com_velocity = u + w.cross(top.com_offset * f_hat);
  s.contact_point = Eigen::Vector3d(y[idx::x], y[idx::x + 1], 0.0);
  s.figure_axis = f_hat;
  s.angular_velocity = w;
  s.spin = w.dot(f_hat);
  s.has_rotor = top.has_rotor;
  s.rotor_spin = top.has_rotor ? s.spin + y[idx::nu] : 0.0;
  s.spin_phase = y[idx::psi];
  if (model.kind == ModelKind::adiabatic) {
    // The reduced model slides at s* with mu(s*) = tan(alpha) and N = m g cos(alpha) by construction.
    s.slip = stationary.slip;
    s.mu = std::tan(std::abs(model.plane.inclination));
    s.normal_force = top.mass * model.plane.gravity * std::cos(model.plane.inclination);
    s.friction_force = -top.mass * Eigen::Vector3d(model.plane.g_plane.x(), model.plane.g_plane.y(), 0.0);
    s.com_acceleration.setZero();
  } else {
    s.slip = dyn.contact.slip;
    s.mu = dyn.mu;
    s.normal_force = dyn.normal_force;
    s.friction_force = dyn.friction_force;
    s.com_acceleration = dyn.a_cm;
  }
  s.phi = (u.x() == 0.0 && u.y() == 0.0) ? 0.0 : std::atan2(-u.y(), u.x());
  s.has_stationary_state = stationary.exists && stationary.phi_defined;
  s.phi_star = s.has_stationary_state ? stationary.phi : 0.0;
  s.indicators = regime_indicators(model, y, dyn);
  if (model.kind == ModelKind::adiabatic) s.indicators = RegimeIndicators{};
  s.fault = model.kind == ModelKind::full ? fault_of(dyn.margins) : ContactFault::none;
  s.regime = classify(model.regime, s.indicators, s.fault != ContactFault::none, previous);
  s.energy = mechanical_energy(model, y);
  s.dissipated_work = y[idx::w_diss];
  s.energy_balance_residual = balance.residual(model, y);
  return s;
}

}  // namespace top_sim
