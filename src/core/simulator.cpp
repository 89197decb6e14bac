// The Simulator: a driver over its stages (simulator_impl.hpp lists them, each in its file) and the one commit.
#include "top_sim/simulator.hpp"

#include <algorithm>
#include <cmath>

#include "simulator_impl.hpp"
#include "top_sim/adiabatic.hpp"
#include "angular_momentum.hpp"
#include "top_sim/format.hpp"
#include "shape_motion.hpp"

namespace top_sim {

namespace {

using Clock = std::chrono::steady_clock;

// Consecutive steps too small to change t (below its resolution: motion far too fast) before the run is stopped.
constexpr int kMaxStalledSteps = 1000;
// The stiff slip-onset layer (mu(0) > 0, |v_t| small, slipping) is crossed by rosenbrock4 below this many
// stick speeds and handed back above twice that (explicit steps are stable there at the usual step sizes).
constexpr double kLayerWidth = 100.0;

// `budget` wall seconds after `start`; never with an infinite budget.
Clock::time_point deadline_after(Clock::time_point start, double budget) {
  if (!std::isfinite(budget)) return Clock::time_point::max();
  return start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::max(budget, 0.0)));
}

std::string stalled_message(double t) {
  return describe(ContactFault::numerical, 0.0, t) + " (" + std::to_string(kMaxStalledSteps) +
         " steps too small to change t = " + format_number(t) + " s: the motion is too fast for the time's resolution)";
}

}  // namespace

SimulatorImpl::SimulatorImpl(const Scene& scene)
    : energy_residual_limit_(scene.integrator.max_energy_residual), model_(scene.model), scene_(scene) {
  stepper_ = make_stepper(
      scene_.integrator,
      [this](const StateVector& y, StateVector& dydt) {
        if (model_.kind == ModelKind::adiabatic)  // the geometry solved once per model, not per right-hand side
          adiabatic_derivative(model_, stationary_geometry_, y, dydt);
        else
          model_derivative(model_, contact_model_, mode_, y, dydt, &record_);
      },
      [this](const StateVector& y, StateVector& h) { jacobian_difference_steps(model_, mode_, y, h); },
      [this](const StateVector& y, bool inside) { return in_stiff_layer(y, inside); },
      [this](const StateVector& y) { return angular_momentum_azimuth(model_, y); });
  reset();
}

// Order of actions, each pass until t_target or a fault:
//   1. the commands and scene events due are applied at this step boundary (command_queue.cpp);
//   2. the stepper steps towards the next stop (t_target or the next scene event); each step's dense output is
//      scanned for its first event (event_location.cpp), the regime clock runs up to it (regime_clock.cpp, which
//      may hand a sleeping top to the reduced model: auto_handover.cpp), and the event is applied
//      (event_application.cpp), restarting the stepper at it;
//   3. the state at the stop is committed.
// A finite budget ends the call at the first step boundary after its deadline (the stepper continues from there).
bool SimulatorImpl::advance_to(double t_target, double budget_seconds, Clock::time_point start) {
  StepBudget budget{std::isfinite(budget_seconds), start, deadline_after(start, budget_seconds), t_, false};
  while (!stopped() && t_ < t_target) {
    apply_pending();  // 1
    if (stopped()) break;
    const double t_stop = std::min(t_target, next_event_t_);
    const Reach reach = step_to(t_stop, budget);  // 2
    if (reach == Reach::out_of_budget) return false;
    if (reach == Reach::fault) break;
    commit_stop(t_stop);  // 3
  }
  if (!stopped()) apply_pending();  // events due exactly at t_target take effect now
  return true;
}

// Steps and scans until the scan reaches t_stop; events on the way are applied (the stepper restarts at each).
SimulatorImpl::Reach SimulatorImpl::step_to(double t_stop, StepBudget& b) {
  int stalled = 0;
  try {
    for (;;) {
      // Events are scanned on the dense output up to t_stop only: an event beyond it waits for the next call.
      const double t_scan = std::min(stepper_->time(), t_stop);
      if (scanned_ < t_scan && !scan_step(t_scan)) {
        if (stopped()) return Reach::fault;
        b.worked = true;
        continue;  // the state is at the event; the stepper restarted there
      }
      if (t_scan >= t_stop) return Reach::stop;
      // Out of budget after a scanned step or a handled event (steps that all end in events count too).
      if (b.limited && (b.worked ? Clock::now() : b.start) >= b.deadline &&
          (stepper_->time() > t_ || t_ > b.t_entry)) {
        if (stepper_->time() > t_) commit(stepper_->state(), stepper_->time());  // a scanned step boundary
        return Reach::out_of_budget;
      }
      const double t_before = stepper_->time();
      stepper_->step(t_stop);
      b.worked = true;
      if (!all_finite(stepper_->state())) {
        stop_at_step_start("");
        return Reach::fault;
      }
      stalled = stepper_->time() > t_before ? 0 : stalled + 1;
      if (stalled > kMaxStalledSteps) {  // y_ and t_ stay at the last boundary: the steps never left it
        fail(ContactFault::numerical, stalled_message(t_before));
        return Reach::fault;
      }
    }
  } catch (const std::exception& e) {  // odeint gives up when it cannot find an acceptable step
    fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, stepper_->time()) + " (" + e.what() + ")");
    return Reach::fault;
  }
}

// The state at t_stop: the step's end, the scan's interpolation at it, or the dense output there.
void SimulatorImpl::commit_stop(double t_stop) {
  if (stepper_->time() <= t_stop) return commit(stepper_->state(), t_stop);
  if (scan_end_.valid && scan_end_.t == t_stop) return commit(scan_end_.y, t_stop);
  StateVector y;
  stepper_->state_at(t_stop, y);
  commit(y, t_stop);
}

// The one place a new state and time take effect: every value derived from the old ones is stale from here.
void SimulatorImpl::commit(const StateVector& y, double t) {
  y_ = y;
  t_ = t;
  ++revision_;
}

bool SimulatorImpl::in_stiff_layer(const StateVector& y, bool inside) const {
  if (mode_ != ContactMode::slipping || model_.kind != ModelKind::full) return false;
  if (has_shapes(model_)) [[unlikely]] {  // the touching shape's slip, not the tip sphere's
    const ContactKinematics k = shape_kinematics(model_, y);
    return k.v_t.norm() < (inside ? 2.0 : 1.0) * layer_width_ &&
           (layer_kink_at_rest_ || friction_coefficient(model_.friction, k.slip) > 0.0);
  }
  const double speed = contact_velocity(model_, in_plane_velocity(y), angular_velocity(y)).norm();
  if (!(speed < (inside ? 2.0 : 1.0) * layer_width_)) return false;
  // A kink at v_t = 0 needs friction there: mu(0) > 0, or a slip near 1 (no rolling: a point tip, no spin).
  if (layer_kink_at_rest_) return true;
  const ContactKinematics k = contact_kinematics(model_, in_plane_velocity(y), angular_velocity(y));
  return friction_coefficient(model_.friction, k.slip) > 0.0;
}

void SimulatorImpl::reset() {
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.clear();
    has_pending_.store(false, std::memory_order_relaxed);
    model_ = scene_.model;
    stopped_refusal_.clear();
  }
  StateVector y = initial_state(scene_);
  t_origin_ = t_;
  next_event_ = 0;
  schedule_next_event();
  fault_ = ContactFault::none;
  end_state_ = EndState::none;
  fault_message_.clear();
  end_message_.clear();
  max_energy_residual_seen_ = 0.0;
  mode_seconds_.fill(0.0);
  switches_.clear();
  switch_count_ = 0;
  instant_switches_ = 0;
  clustered_switches_ = 0;
  last_switch_t_ = -1.0;
  // A stick impulse here is part of the initial state; a Painleve state comes back as slipping, and restart()
  // reports it from the slipping margins.
  model_.shapes.touching = 0;  // the start places shapes[0] on the plane (scene.cpp)
  model_.shapes.second = kNoShape;
  model_.shapes.stuck = {false, false};
  mode_ = initial_mode(model_, y).mode;
  mode_since_ = t_;
  restart(y, t_, true);
  stationary_geometry_ = stationary_geometry(model_);
  // The regime clock restarts here: its first point is the initial state, classified from nutating.
  cadence_t_ = t_;
  cadence_k_ = 0;
  cadence_regime_ = Regime::nutating;
  regime_seconds_.fill(0.0);
  reduction_ = Reduction{};
  handover_due_ = false;
  handovers_ = 0;
  reduced_seconds_ = 0.0;
  if (!stopped()) cadence_point(t_, y_);
  take_handover();  // a scene that starts asleep hands over at once
}

// After any jump of the state, the model or the mode: commit y at t (projected onto the sleeping state under the
// reduced model), optionally re-base the energy balance (commands inject energy; events book their losses in
// W_diss and keep it), arm the new mode's margins, check for faults.
void SimulatorImpl::restart(const StateVector& y_new, double t, bool rebase_energy) {
  StateVector y = y_new;  // y_new may be y_ itself
  if (model_.kind == ModelKind::adiabatic) project_to_stationary(model_, stationary_geometry_, y);
  commit(y, t);
  if (rebase_energy) balance_.rebase(model_, y_);
  cos_max_tilt_ = std::cos(model_.top.max_tilt);
  contact_model_ = contact_model(model_);
  layer_width_ = kLayerWidth * std::max(model_.contact.stick_speed, model_.regularization_speed);
  layer_kink_at_rest_ = raw_friction_coefficient(model_.friction, 0.0) > 0.0;
  select_stepper();
  stepper_->reset(y_, t_);  // before it, the stepper's state is no argument of a right-hand side of this model
  scan_end_.valid = false;
  scanned_ = t_;
  last_margins_ = margins_of(model_, mode_, y_, cos_max_tilt_);
  lift_armed_ = last_margins_.lift > 0.0;
  transfer_armed_ = last_margins_.transfer > 0.0;
  // A shape that has just let go separates from gap 0: armed at once, for its return may come within the first step
  // (the tippe top's stem handed over at 1e-5 m/s against 10 m/s^2 is back in 2 us).
  touch_armed_ = last_margins_.touch > 0.0 || (last_margins_.touch != ModeMargins::kNone &&
                                                has_shapes(model_) && free_shape_gap_rate(model_, y_) > 0.0);
  if (stopped()) return;
  if (!all_finite(y_)) {
    fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t_));
  } else if (model_.kind == ModelKind::full) {
    if (last_margins_.painleve <= 0.0)
      fail(ContactFault::painleve, describe(ContactFault::painleve, last_margins_.painleve, t_));
    else if (last_margins_.end < 0.0)
      end(tilt_end_state(model_), last_margins_.end);
  }
}

// A numerical fault in the last step: the state goes back to the step's start (or stays at the last committed
// state when even that interpolates to non-finite values), so snapshots stay finite after the fault.
void SimulatorImpl::stop_at_step_start(const std::string& detail) {
  StateVector y0;
  const double t0 = stepper_->previous_time();
  stepper_->state_at(t0, y0);
  if (all_finite(y0) && std::isfinite(mechanical_energy(model_, y0))) commit(y0, t0);
  fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t_) + detail);
}

void SimulatorImpl::fail(ContactFault fault, const std::string& message) {
  if (stopped()) return;
  fault_ = fault;
  fault_message_ = message;
  refuse_commands(std::string("the run stopped on the contact fault ") + to_string(fault));
}

void SimulatorImpl::end(EndState state, double margin) {
  if (stopped()) return;
  end_state_ = state;
  end_message_ = describe(state, margin, t_);
  refuse_commands(std::string("the run ended in the end state ") + to_string(state));
}

// A stopped run's time no longer moves: a command would be queued and never applied, so submit() refuses it.
void SimulatorImpl::refuse_commands(const std::string& why) {
  std::lock_guard<std::mutex> lock(pending_mutex_);
  stopped_refusal_ = why + " at t = " + format_number(t_) + " s: reset it before commanding it (nothing applied)";
}

// The user's surface: each call is the stage's.
Simulator::Simulator(const Scene& scene) : impl_(std::make_unique<SimulatorImpl>(scene)) {}
Simulator::~Simulator() = default;

bool Simulator::advance_to(double t, double budget_seconds) {
  const bool budgeted = std::isfinite(budget_seconds);
  return impl_->advance_to(t, budget_seconds, budgeted ? Clock::now() : Clock::time_point());
}
bool Simulator::advance_to(double t, double budget_seconds, Clock::time_point start) {
  return impl_->advance_to(t, budget_seconds, start);
}
std::string Simulator::submit(const Command& command) { return impl_->submit(command); }
void Simulator::reset() { impl_->reset(); }
double Simulator::time() const { return impl_->t_; }
const StateVector& Simulator::state() const { return impl_->y_; }
const Model& Simulator::model() const { return impl_->model_; }
const Scene& Simulator::scene() const { return impl_->scene_; }
Snapshot Simulator::snapshot() const { return impl_->snapshot(); }
TopPose Simulator::pose() const { return top_pose(impl_->model_, impl_->y_, impl_->t_); }
const StepperStats& Simulator::stats() const { return impl_->numeric_stepper().stats; }
ContactFault Simulator::fault() const { return impl_->fault_; }
EndState Simulator::end_state() const { return impl_->end_state_; }
bool Simulator::stopped() const { return impl_->stopped(); }
const std::string& Simulator::fault_message() const { return impl_->fault_message_; }
const std::string& Simulator::end_message() const { return impl_->end_message_; }
const StationaryState& Simulator::stationary() const { return impl_->sample().stationary; }
double Simulator::max_energy_residual() const { return impl_->max_energy_residual_seen_; }
ContactMode Simulator::contact_mode() const { return impl_->mode_; }
std::array<double, kContactModeCount> Simulator::mode_seconds() const { return impl_->mode_seconds(); }
std::vector<ModeSwitch> Simulator::take_mode_switches() { return impl_->take_mode_switches(); }
std::uint64_t Simulator::mode_switch_count() const { return impl_->switch_count_; }
std::array<double, kRegimeCount> Simulator::regime_seconds() const { return impl_->regime_seconds(); }
std::uint64_t Simulator::handovers() const { return impl_->handovers_; }
double Simulator::reduced_seconds() const { return impl_->reduced_seconds(); }
std::uint64_t Simulator::layer_steps() const { return impl_->numeric_stepper().layer_steps(); }

}  // namespace top_sim
