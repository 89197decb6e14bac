// The Simulator: time, stepper, contact modes and their events, commands, faults (physics.md sections 4, 8, 9).
#include "top_sim/simulator.hpp"

#include "top_sim/angular_momentum.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

#include "top_sim/adiabatic.hpp"
#include "counters.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/format.hpp"
#include "top_sim/impact.hpp"
#include "top_sim/orientation.hpp"

namespace top_sim {

namespace {

// Samples per nutation period where a margin is near its threshold (physics.md section 9: the shortest sign dips,
// e.g. the 34 us of negative N in the first 76 us hop at 5000 rad/s, last about 1/20 of a nutation period).
constexpr double kSamplesPerNutation = 40.0;
constexpr int kMaxSamplesPerStep = 4096;
constexpr int kMinFlightSamples = 4;      // a whole hop may fit in one step: always look inside it
constexpr int kMaxInstantSwitches = 100;  // mode switches at one instant before the Zeno guard stops the run
// Consecutive steps too small to change t (below its resolution: motion far too fast) before the run is stopped.
constexpr int kMaxStalledSteps = 1000;
// Guard bands: a margin this close to its threshold at either end of a step makes the step sampled inside.
constexpr double kForceGuard = 0.5;       // N, F_n, rolling margin: fraction of the weight m g
constexpr double kStickGuard = 1.0e3;     // stick function: |v_t| < 1000 v_stick
constexpr double kPainleveGuard = 0.5;    // m n.K d (1 without friction)
constexpr double kTiltGuard = 0.05;       // n . f_hat - cos(theta_max)
// The stiff slip-onset layer (mu(0) > 0, |v_t| small, slipping) is crossed by rosenbrock4 below this many
// stick speeds and handed back above twice that (explicit steps are stable there at the usual step sizes).
constexpr double kLayerWidth = 100.0;

ModeMargins margins_of(const Model& model, ContactMode mode, const StateVector& y) {
  Dynamics dyn;
  evaluate_dynamics(model, mode, y, dyn);
  return dyn.margins;
}

// Spacing of event samples: 1/40 of the nutation period 2 pi I_d / |L_total . f_hat| (infinite without spin).
double sample_spacing(const Model& model, const StateVector& y) {
  const Top& top = model.top;
  const double J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double w_f = shell_spin(y);
  const double axial = std::abs((top.inertia_axial - J) * w_f + J * (w_f + (top.has_rotor ? y[idx::nu] : 0.0)));
  if (!(axial > 0.0)) return std::numeric_limits<double>::infinity();
  return 2.0 * M_PI * top.inertia_transverse / axial / kSamplesPerNutation;
}

bool near_threshold(const Model& model, const ModeMargins& m, ContactMode mode) {
  if (mode == ContactMode::flight) return true;
  const double weight = model.top.mass * model.plane.gravity;  // lift is a force; transfer is already in weights
  const double transfer_guard = mode == ContactMode::slipping ? kStickGuard : kForceGuard;
  return m.lift < kForceGuard * weight || m.transfer < transfer_guard || m.painleve < kPainleveGuard ||
         m.tilt < kTiltGuard;
}

// The part of a sample of a finite state that is not finite (products of large speeds overflow), or nullptr.
const char* overflowed_part(const SampleAnalysis& a) {
  if (!std::isfinite(a.energy)) return "the energy";
  const Dynamics& d = a.dynamics;
  if (!(std::isfinite(d.mu) && std::isfinite(d.normal_force) && std::isfinite(d.nu_dot) &&
        std::isfinite(d.contact.slip) && d.contact_force.allFinite() && d.omega_dot.allFinite() && d.a_cm.allFinite()))
    return "the dynamics";
  const RegimeIndicators& i = a.indicators;
  if (!(std::isfinite(i.nutation_angle) && std::isfinite(i.nutation_rate) && std::isfinite(i.acceleration) &&
        std::isfinite(i.speed)))
    return "the regime indicators";
  return nullptr;
}

// What a regime cadence point needs of a state: the dynamics, the indicators and the energy, with no stationary
// solve: the indicators read only the model's answer (exists, slip_unstable), which no spin changes. A sample
// adds the stationary state at its spin. analysis_of takes the dynamics and the energy evaluated already.
SampleAnalysis analysis_of(const Model& model, const StateVector& y, const Dynamics& dynamics, double energy,
                           const StationaryState& model_stationary) {
  SampleAnalysis a;
  a.dynamics = dynamics;
  if (model.kind != ModelKind::adiabatic) a.indicators = regime_indicators(model, y, a.dynamics, model_stationary);
  a.energy = energy;
  return a;
}

SampleAnalysis cadence_analysis(const Model& model, ContactMode mode, const StateVector& y,
                                const StationaryState& model_stationary) {
  Dynamics dynamics;
  evaluate_dynamics(model, mode, y, dynamics);
  return analysis_of(model, y, dynamics, mechanical_energy(model, y), model_stationary);
}

std::string stalled_message(double t) {
  return describe(ContactFault::numerical, 0.0, t) + " (" + std::to_string(kMaxStalledSteps) +
         " steps too small to change t = " + format_number(t) + " s: the motion is too fast for the time's resolution)";
}

std::string impact_painleve_message(double t, double denominator) {
  std::ostringstream os;
  os << "t = " << format_number(t) << " s: ";
  os << "Painleve at impact: the sliding impulse has no admissible normal part (n . K (n - mu_i t_hat) = "
     << denominator << " <= 0); reduce the friction";
  return os.str();
}

}  // namespace

// What one sample of the dense output shows; when several show at once, the first in this order is handled.
enum class Simulator::Event { none, painleve, lift_off, touchdown, transfer, fallen };

Simulator::Simulator(const Scene& scene)
    : energy_residual_limit_(scene.integrator.max_energy_residual), model_(scene.model), scene_(scene) {
  stepper_ = make_stepper(
      scene_.integrator,
      [this](const StateVector& y, StateVector& dydt) {
        model_derivative(model_, contact_model_, mode_, y, dydt, &record_);
      },
      [this](const StateVector& y, StateVector& h) { jacobian_difference_steps(model_, mode_, y, h); },
      [this](const StateVector& y, bool inside) { return in_stiff_layer(y, inside); },
      [this](const StateVector& y) { return angular_momentum_azimuth(model_, y); });
  reset();
}

bool Simulator::in_stiff_layer(const StateVector& y, bool inside) const {
  if (mode_ != ContactMode::slipping || model_.kind != ModelKind::full) return false;
  const double speed = contact_velocity(model_, in_plane_velocity(y), angular_velocity(y)).norm();
  if (!(speed < (inside ? 2.0 : 1.0) * layer_width_)) return false;
  // A kink at v_t = 0 needs friction there: mu(0) > 0, or a slip near 1 (no rolling: a point tip, no spin).
  if (layer_kink_at_rest_) return true;
  const ContactKinematics k = contact_kinematics(model_, in_plane_velocity(y), angular_velocity(y));
  return friction_coefficient(model_.friction, k.slip) > 0.0;
}

void Simulator::reset() {
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.clear();
    has_pending_.store(false, std::memory_order_relaxed);
    model_ = scene_.model;
  }
  y_ = initial_state(scene_);
  t_origin_ = t_;
  next_event_ = 0;
  schedule_next_event();
  fault_ = ContactFault::none;
  fault_message_.clear();
  max_energy_residual_seen_ = 0.0;
  mode_seconds_.fill(0.0);
  switches_.clear();
  switch_count_ = 0;
  instant_switches_ = 0;
  last_switch_t_ = -1.0;
  // A stick impulse here is part of the initial state; a Painleve state comes back as slipping, and
  // restart_stepper() reports it from the slipping margins.
  mode_ = initial_mode(model_, y_).mode;
  mode_since_ = t_;
  restart_stepper(true);
  invalidate_sample();
  stationary_geometry_ = stationary_geometry(model_);
  // The regime cadence restarts here: its first point is the initial state, classified from nutating.
  cadence_t_ = t_;
  cadence_k_ = 0;
  cadence_regime_ = Regime::nutating;
  regime_seconds_.fill(0.0);
  reduction_ = Reduction{};
  handover_.due = false;
  handovers_ = 0;
  reduced_seconds_ = 0.0;
  if (fault_ == ContactFault::none) cadence_point(t_, y_);
  take_handover();  // a scene that starts asleep hands over at once
}

// After any jump of the state, the model or the mode: optionally re-base the energy balance (commands inject
// energy; events book their losses in W_diss and keep it), arm the new mode's margins, check for faults.
void Simulator::restart_stepper(bool rebase_energy) {
  if (model_.kind == ModelKind::adiabatic) project_to_stationary(model_, y_);
  if (rebase_energy) balance_.rebase(model_, y_);
  cos_max_tilt_ = std::cos(model_.top.max_tilt);
  contact_model_ = contact_model(model_);
  layer_width_ = kLayerWidth * std::max(model_.contact.stick_speed, model_.regularization_speed);
  layer_kink_at_rest_ = raw_friction_coefficient(model_.friction, 0.0) > 0.0;
  select_stepper();
  stepper_->reset(y_, t_);  // before it, the stepper's state is no argument of a right-hand side of this model
  scan_end_.valid = false;
  scanned_ = t_;
  last_margins_ = margins_of(model_, mode_, y_);
  lift_armed_ = last_margins_.lift > 0.0;
  transfer_armed_ = last_margins_.transfer > 0.0;
  if (fault_ != ContactFault::none) return;
  if (!all_finite(y_)) {
    fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t_));
  } else if (model_.kind == ModelKind::full) {
    if (last_margins_.painleve <= 0.0)
      fail(ContactFault::painleve, describe(ContactFault::painleve, last_margins_.painleve, t_));
    else if (last_margins_.tilt < 0.0)
      fail(ContactFault::fallen, describe(ContactFault::fallen, last_margins_.tilt, t_));
  }
}

// A numerical fault in the last step: the state goes back to the step's start (or stays at the last committed
// state when even that interpolates to non-finite values), so snapshots stay finite after the fault.
void Simulator::stop_at_step_start(const std::string& detail) {
  StateVector y0;
  const double t0 = stepper_->previous_time();
  stepper_->state_at(t0, y0);
  if (all_finite(y0) && std::isfinite(mechanical_energy(model_, y0))) {
    y_ = y0;
    t_ = t0;
    invalidate_sample();
  }
  fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t_) + detail);
}

void Simulator::fail(ContactFault fault, const std::string& message) {
  if (fault_ != ContactFault::none) return;
  fault_ = fault;
  fault_message_ = message;
}

std::string Simulator::submit(const Command& command) {
  std::lock_guard<std::mutex> lock(pending_mutex_);  // the owner writes model_ only under it
  const std::string error = validate(command, model_);
  if (!error.empty()) return error;
  pending_.push_back(command);
  has_pending_.store(true, std::memory_order_release);
  return "";
}

// A contact that a command changed (spin, friction, inclination) may no longer hold in its mode: the closing rule
// decides again (a flight stays a flight).
void Simulator::reclose_contact() {
  if (mode_ == ContactMode::flight || !has_contact_modes(model_)) return;
  const ContactMode before = mode_;
  const double e0 = mechanical_energy(model_, y_);
  const ClosingResult c = close_contact(model_, y_);
  const double loss = e0 - mechanical_energy(model_, y_);  // the stick impulse's loss, if any
  y_[idx::w_diss] += loss;
  if (c.mode != before) {  // a Painleve state comes back as slipping: restart_stepper() reports it
    const ModeSwitchKind kind = c.mode == ContactMode::flight  ? ModeSwitchKind::lift_off
                                : c.mode == ContactMode::rolling ? ModeSwitchKind::stick
                                                                 : ModeSwitchKind::slip;
    switch_mode(c.mode, kind, -loss);
  }
}

bool Simulator::scene_event_due() const { return next_event_t_ <= t_; }

void Simulator::schedule_next_event() {
  next_event_t_ = next_event_ < scene_.events.size() ? t_origin_ + scene_.events[next_event_].t
                                                     : std::numeric_limits<double>::infinity();
}

void Simulator::apply_pending() {
  // Most calls find nothing: no lock then (an uncontended lock still costs a cold cache line per top and call).
  if (!scene_event_due() && !has_pending_.load(std::memory_order_acquire)) return;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    std::vector<Command> due;
    due.swap(pending_);
    has_pending_.store(false, std::memory_order_relaxed);
    while (scene_event_due()) {
      due.push_back(scene_.events[next_event_++].command);
      schedule_next_event();
    }
    if (due.empty()) return;
    // Under auto every command and event lands in the full model.
    if (model_.automatic.enabled && model_.kind != ModelKind::full) resume_full();
    reduction_ = Reduction{};
    for (const Command& c : due) apply_command(c, model_, y_);  // model_ under the lock: submit() reads it
  }
  invalidate_sample();
  stationary_geometry_ = stationary_geometry(model_);  // the inclination or the law may have changed
  reclose_contact();
  restart_stepper(true);
}

namespace {

// `budget` wall seconds after `start`; never with an infinite budget.
std::chrono::steady_clock::time_point deadline_after(std::chrono::steady_clock::time_point start, double budget) {
  using Clock = std::chrono::steady_clock;
  if (!std::isfinite(budget)) return Clock::time_point::max();
  return start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::max(budget, 0.0)));
}

}  // namespace

bool Simulator::advance_to(double t_target, double budget_seconds) {
  const bool budgeted = std::isfinite(budget_seconds);
  return advance_to(t_target, budget_seconds, budgeted ? std::chrono::steady_clock::now()
                                                        : std::chrono::steady_clock::time_point());
}

bool Simulator::advance_to(double t_target, double budget_seconds, std::chrono::steady_clock::time_point start) {
  using Clock = std::chrono::steady_clock;
  const bool budgeted = std::isfinite(budget_seconds);
  const Clock::time_point deadline = deadline_after(start, budget_seconds);
  const double t_entry = t_;
  bool worked = false;  // a step or an event since `start`: before one, the clock still reads about `start`
  while (fault_ == ContactFault::none && t_ < t_target) {
    apply_pending();
    if (fault_ != ContactFault::none) break;
    double t_stop = t_target;
    t_stop = std::min(t_stop, next_event_t_);
    int stalled = 0;
    try {
      for (;;) {
        // Events are scanned on the dense output up to t_stop only: an event beyond it waits for the next call.
        const double t_scan = std::min(stepper_->time(), t_stop);
        if (scanned_ < t_scan && !scan_events(t_scan)) {
          if (fault_ != ContactFault::none) break;
          worked = true;
          continue;  // the state is at the event; the stepper restarted there
        }
        if (t_scan >= t_stop) break;
        // Out of budget after a scanned step or a handled event (steps that all end in events count too).
        if (budgeted && (worked ? Clock::now() : start) >= deadline && (stepper_->time() > t_ || t_ > t_entry)) {
          if (stepper_->time() > t_) {
            y_ = stepper_->state();  // a scanned step boundary: the stepper continues from here next time
            t_ = stepper_->time();
            invalidate_sample();
          }
          return false;
        }
        const double t_before = stepper_->time();
        stepper_->step(t_stop);
        worked = true;
        if (!all_finite(stepper_->state())) {
          stop_at_step_start("");
          break;
        }
        stalled = stepper_->time() > t_before ? 0 : stalled + 1;
        if (stalled > kMaxStalledSteps) {  // y_ and t_ stay at the last boundary: the steps never left it
          fail(ContactFault::numerical, stalled_message(t_before));
          break;
        }
      }
    } catch (const std::exception& e) {  // odeint gives up when it cannot find an acceptable step
      fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, stepper_->time()) + " (" + e.what() + ")");
    }
    if (fault_ != ContactFault::none) break;
    if (stepper_->time() <= t_stop) y_ = stepper_->state();
    else if (scan_end_.valid && scan_end_.t == t_stop) y_ = scan_end_.y;  // the scan at t_stop interpolated it
    else stepper_->state_at(t_stop, y_);
    t_ = t_stop;
    invalidate_sample();
  }
  if (fault_ == ContactFault::none) apply_pending();  // events due exactly at t_target take effect now
  return true;
}

// Which event a sample shows: faults, then lift-off / touchdown, then stick / slip (armed margins only).
Simulator::Event Simulator::sample_event(const ModeMargins& m, const StateVector& y) const {
  if (model_.kind != ModelKind::full) return Event::none;
  if (m.painleve <= 0.0) return Event::painleve;
  if (mode_ == ContactMode::flight) {
    // Touchdown: the gap is down to 0 while closing; a flight starts at gap 0 with a non-negative rate.
    if (y[idx::gap] <= 0.0 && y[idx::gap_rate] < 0.0) return Event::touchdown;
  } else if (lift_armed_ && m.lift < 0.0) {
    return Event::lift_off;
  }
  if (transfer_armed_ && m.transfer <= 0.0) return Event::transfer;
  if (m.tilt < 0.0) return Event::fallen;
  return Event::none;
}

// Scans the last step's dense output from scanned_ to t_end for events. Returns true when none fired; otherwise
// the state is at the located event (or fault) instant, the event is handled and the stepper restarted.
bool Simulator::scan_events(double t_end) {
  const double t0 = scanned_;
  const StateVector& y1 = begin_scan(t_end);
  const double residual = balance_.residual(scan_end_.energy, y1);
  max_energy_residual_seen_ = std::max(max_energy_residual_seen_, residual);
  if (!(residual <= energy_residual_limit_)) {  // an unstable step: its events would be fiction
    stop_at_step_start(" (the energy balance drifted by " + format_number(residual) + " of the energy scale, over " +
                       "integrator.max_energy_residual = " + format_number(scene_.integrator.max_energy_residual) +
                       ": the step is unstable)");
    return false;
  }
  if (closed_flight_) return scan_flight(t_end, y1);
  if (model_.kind != ModelKind::full) return scan_reduced(t_end, y1);
  const ModeMargins m1 = step_end_margins(y1, sample_.dynamics, scan_end_.has_dynamics);
  int samples = 1;
  if (near_threshold(model_, last_margins_, mode_) || near_threshold(model_, m1, mode_)) {
    const double n = std::ceil((t_end - t0) / sample_spacing(model_, y1));
    samples = static_cast<int>(std::min<double>(std::isfinite(n) ? n : 1.0, kMaxSamplesPerStep));
    samples = std::max(samples, mode_ == ContactMode::flight ? kMinFlightSamples : 1);
  }
  double t_prev = t0;
  StateVector yk;
  for (int k = 1; k <= samples; ++k) {
    const double tk = k == samples ? t_end : t0 + (t_end - t0) * k / samples;
    if (k == samples) yk = y1; else stepper_->state_at(tk, yk);
    const ModeMargins mk = k == samples ? m1 : margins_of(model_, mode_, yk);
    if (sample_event(mk, yk) != Event::none) {
      // Bisect between the last quiet sample and this one for the first instant an event fires.
      double lo = t_prev, hi = tk;
      StateVector ym;
      for (int i = 0; i < 80 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++i) {
        const double mid = 0.5 * (lo + hi);
        stepper_->state_at(mid, ym);
        if (sample_event(margins_of(model_, mode_, ym), ym) != Event::none) hi = mid; else lo = mid;
      }
      run_cadence(hi);  // the regime's points up to the event, on this step's dense output
      if (fault_ != ContactFault::none || take_handover()) return false;
      stepper_->state_at(hi, y_);
      t_ = hi;
      invalidate_sample();
      const ModeMargins mh = margins_of(model_, mode_, y_);
      Event event = sample_event(mh, y_);
      if (event == Event::none) event = sample_event(mk, yk);  // rounding at the boundary: keep the sample's verdict
      handle_event(event, mh);
      return false;
    }
    if (mk.lift > 0.0) lift_armed_ = true;
    if (mk.transfer > 0.0) transfer_armed_ = true;
    t_prev = tk;
  }
  last_margins_ = m1;
  scanned_ = t_end;
  scan_end_.valid = t_end < stepper_->time();  // a tick's end: its state and sample may read this scan's
  run_cadence(t_end);
  return fault_ == ContactFault::none && !take_handover();
}

// The state at t_end on the last step's dense output, and its energy, into scan_end_ (valid once the scan of a
// tick's end has completed); the sample is invalidated, as the scan's margins may leave their dynamics in it.
const StateVector& Simulator::begin_scan(double t_end) {
  scan_end_.valid = false;
  scan_end_.t = t_end;
  if (t_end < stepper_->time()) stepper_->state_at(t_end, scan_end_.y); else scan_end_.y = stepper_->state();
  scan_end_.energy = mechanical_energy(model_, scan_end_.y);
  invalidate_sample();
  return scan_end_.y;
}

// The margins at a step's end: dopri5 (first same as last) has just evaluated the right-hand side there, so
// its recorded contact force serves when y is the stepper's state in every bit (else one full evaluation).
ModeMargins Simulator::step_end_margins(const StateVector& y, Dynamics& evaluated, bool& has_evaluated) {
  ModeMargins m;
  has_evaluated = false;
  if (stepper_->state_was_last_rhs() && std::memcmp(y.data(), stepper_->state().data(), sizeof(StateVector)) == 0 &&
      margins_from_record(model_, mode_, y, record_, cos_max_tilt_, m))
    return m;
  evaluate_dynamics(model_, mode_, y, evaluated);
  has_evaluated = true;
  return evaluated.margins;
}

void Simulator::handle_event(Event event, const ModeMargins& m) {
  switch (event) {
    case Event::painleve:
      fail(ContactFault::painleve, describe(ContactFault::painleve, m.painleve, t_));
      return;
    case Event::fallen:
      fail(ContactFault::fallen, describe(ContactFault::fallen, m.tilt, t_));
      return;
    case Event::transfer:
      if (mode_ == ContactMode::slipping) {
        const double e0 = mechanical_energy(model_, y_);
        apply_stick_impulse(model_, y_);
        const double loss = e0 - mechanical_energy(model_, y_);
        y_[idx::w_diss] += loss;
        switch_mode(ContactMode::rolling, ModeSwitchKind::stick, -loss);
      } else {
        switch_mode(ContactMode::slipping, ModeSwitchKind::slip);  // starts with v_t = 0
      }
      break;
    case Event::lift_off:
      y_[idx::gap] = y_[idx::gap_rate] = 0.0;
      switch_mode(ContactMode::flight, ModeSwitchKind::lift_off);
      break;
    case Event::touchdown: {
      y_[idx::gap] = 0.0;
      const double e0 = mechanical_energy(model_, y_);
      const ImpactResult impact = apply_impact(model_, y_);
      if (impact.painleve) {
        fail(ContactFault::painleve, impact_painleve_message(t_, impact.denominator));
        return;
      }
      ContactMode next = ContactMode::flight;  // a bounce flies again
      if (impact.plastic) next = close_contact(model_, y_).mode;  // Painleve: slipping, reported by the restart
      const double loss = e0 - mechanical_energy(model_, y_);  // an impact never raises E: the loss is booked
      y_[idx::w_diss] += loss;
      switch_mode(next, ModeSwitchKind::touchdown, -loss);
      break;
    }
    default:
      return;
  }
  if (fault_ == ContactFault::none) restart_stepper(false);
}

void Simulator::switch_mode(ContactMode mode, ModeSwitchKind kind, double energy_change) {
  mode_seconds_[static_cast<int>(mode_)] += t_ - mode_since_;
  mode_since_ = t_;
  if (switches_.size() < kMaxPendingSwitches) switches_.push_back({t_, kind, mode_, mode, energy_change});
  ++switch_count_;
  mode_ = mode;
  instant_switches_ = t_ - last_switch_t_ > 1e-12 * std::max(1.0, std::abs(t_)) ? 0 : instant_switches_ + 1;
  last_switch_t_ = t_;
  if (instant_switches_ > kMaxInstantSwitches) {
    std::ostringstream os;
    os << describe(ContactFault::numerical, 0.0, t_) << " (" << instant_switches_
       << " contact-mode switches without time advancing, last " << to_string(kind) << " to " << to_string(mode)
       << ")";
    fail(ContactFault::numerical, os.str());
  }
}

// The closed-form flight (flight.hpp) where its dynamics is gravity and no torque, else the numeric stepper; a
// fixed-step method is chosen to see that method's own error, so its flights are stepped too.
void Simulator::select_stepper() {
  const bool closed =
      mode_ == ContactMode::flight && flight_in_closed_form(model_) && is_adaptive(scene_.integrator.method);
  if (closed == closed_flight_) return;
  std::swap(stepper_, parked_);
  closed_flight_ = closed;
}

// A closed-form step ends at the touchdown it located (the only event of a flight) or short of it.
bool Simulator::scan_flight(double t_end, const StateVector& y1) {
  scanned_ = t_end;
  run_cadence(t_end);
  if (fault_ != ContactFault::none) return false;
  if (!(t_end == stepper_->time() && static_cast<const FlightStepper&>(*stepper_).at_touchdown())) return true;
  y_ = y1;
  t_ = t_end;
  invalidate_sample();
  handle_event(Event::touchdown, margins_of(model_, mode_, y_));
  return false;
}

std::array<double, kContactModeCount> Simulator::mode_seconds() const {
  std::array<double, kContactModeCount> s = mode_seconds_;
  s[static_cast<int>(mode_)] += t_ - mode_since_;
  return s;
}

std::vector<ModeSwitch> Simulator::take_mode_switches() {
  std::vector<ModeSwitch> out;
  out.swap(switches_);
  return out;
}

// The regime cadence points in (cadence_t_, t_end], each on the dense output of the step that holds it.
void Simulator::run_cadence(double t_end) {
  while (fault_ == ContactFault::none && !handover_.due) {
    const double tk = t_origin_ + static_cast<double>(cadence_k_ + 1) * kRegimeCadence;
    if (tk > t_end) return;
    ++cadence_k_;
    StateVector yk;
    if (tk >= stepper_->time()) yk = stepper_->state(); else stepper_->state_at(tk, yk);
    cadence_point(tk, yk);
  }
}

// One cadence point: the overflow guard (a run nobody reads still stops) and the classification that carries the
// hysteresis; the interval since the last point counts for that point's regime.
void Simulator::cadence_point(double t, const StateVector& y) {
  const SampleAnalysis a = cadence_analysis(model_, mode_, y, stationary_geometry_.state);
  // A finite state whose energy or dynamics overflow (spins ~1e150 rad/s and up) is no answer either.
  if (const char* part = overflowed_part(a)) {
    y_ = y;  // the top stops at the point that overflowed
    t_ = t;
    invalidate_sample();
    fail(ContactFault::numerical, describe(ContactFault::numerical, 0.0, t) + " (" + part + " overflowed)");
    return;
  }
  regime_seconds_[code(cadence_regime_)] += t - cadence_t_;
  cadence_t_ = t;
  cadence_regime_ = classify(model_.regime, a.indicators, false, cadence_regime_);
  invalidate_sample();  // a read's hysteresis is this point's regime
  if (model_.automatic.enabled && model_.kind == ModelKind::full && mode_ == ContactMode::slipping &&
      (cadence_regime_ == Regime::sleeping || cadence_regime_ == Regime::precessing))
    consider_handover(t, y);
}

// A sleeping top under auto: hand over at this cadence point when the reduction is valid at its spin and the
// decaying modes would still move the contact point by at most model.auto_tolerance (physics.md section 7.1).
void Simulator::consider_handover(double t, const StateVector& y) {
  if (!reduction_applies(reduction_, y)) reduction_ = analyse_reduction(model_, y);
  if (!reduction_.valid || !(remaining_offset(reduction_, y).norm() <= model_.automatic.position_tolerance)) return;
  const Handover h = handover(model_, reduction_, y);
  handover_.due = true;
  handover_.t = t;
  handover_.y = h.y;
  handover_.energy_loss = mechanical_energy(model_, y) - mechanical_energy(model_, h.y);
}

// The handover found by the cadence: the state and time go there, the reduced model takes over.
bool Simulator::take_handover() {
  if (!handover_.due) return false;
  handover_.due = false;
  y_ = handover_.y;
  y_[idx::w_diss] += handover_.energy_loss;  // the decaying modes' energy, as their friction would have taken it
  t_ = handover_.t;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    model_.kind = ModelKind::adiabatic;
  }
  ++handovers_;
  reduced_since_ = t_;
  invalidate_sample();
  restart_stepper(false);
  return true;
}

// The reduced model has no events. Under auto its cadence points are counted; with a spin moved by the bearing,
// the reduction is analysed again, and where it is no longer valid the full model resumes at t_end.
bool Simulator::scan_reduced(double t_end, const StateVector& y1) {
  scanned_ = t_end;
  if (!model_.automatic.enabled) {
    run_cadence(t_end);
    return fault_ == ContactFault::none;
  }
  skip_cadence(t_end);
  if (reduction_applies(reduction_, y1)) return true;
  reduction_ = analyse_reduction(model_, y1);
  if (reduction_.valid) return true;
  y_ = y1;
  t_ = t_end;
  invalidate_sample();
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    resume_full();
  }
  restart_stepper(false);
  return false;
}

// Every cadence point of the reduced model classifies asleep (no nutation, no acceleration): counted, not analysed.
void Simulator::skip_cadence(double t_end) {
  std::uint64_t k = cadence_k_;
  const auto point = [this](std::uint64_t i) { return t_origin_ + static_cast<double>(i) * kRegimeCadence; };
  const double steps = std::floor((t_end - t_origin_) / kRegimeCadence);
  if (steps > static_cast<double>(k) + 1.0) k = static_cast<std::uint64_t>(steps) - 1;
  while (point(k + 1) <= t_end) ++k;  // the same points as run_cadence's, to the bit
  if (k == cadence_k_) return;
  const double first = point(cadence_k_ + 1), last = point(k);
  regime_seconds_[code(cadence_regime_)] += first - cadence_t_;
  regime_seconds_[code(Regime::sleeping)] += last - first;
  cadence_regime_ = Regime::sleeping;
  cadence_t_ = last;
  cadence_k_ = k;
  invalidate_sample();
}

// Called with pending_mutex_ held: it changes model_, which submit() reads from other threads.
void Simulator::resume_full() {
  model_.kind = ModelKind::full;
  reduced_seconds_ += t_ - reduced_since_;
}

double Simulator::reduced_seconds() const {
  return reduced_seconds_ + (model_.automatic.enabled && model_.kind != ModelKind::full ? t_ - reduced_since_ : 0.0);
}

std::array<double, kRegimeCount> Simulator::regime_seconds() const {
  std::array<double, kRegimeCount> s = regime_seconds_;
  s[code(cadence_regime_)] += std::max(0.0, t_ - cadence_t_);  // up to now (a fault stops the time)
  return s;
}

// The sample of the current state, analysed on the first read after a change and classified with the hysteresis
// of the last cadence point (a read commits nothing: the next read or cadence point sees the same history).
const SampleAnalysis& Simulator::sample() const {
  if (!sample_valid_) {
    const bool scanned = scan_end_.valid && scan_end_.has_dynamics && scan_end_.t == t_ &&
                         std::memcmp(scan_end_.y.data(), y_.data(), sizeof(StateVector)) == 0;
    sample_ = scanned ? analyse_sample(model_, y_, stationary_geometry_, sample_.dynamics, scan_end_.energy)
                      : analyse_sample(model_, mode_, y_, stationary_geometry_);
    sample_regime_ = classify(model_.regime, sample_.indicators, false, cadence_regime_);
    sample_valid_ = true;
  }
  return sample_;
}

Snapshot Simulator::snapshot() const {
  const SampleAnalysis& a = sample();
  const Regime regime = fault_ != ContactFault::none ? Regime::contact_fault : sample_regime_;
  Snapshot s = make_snapshot(model_, y_, t_, balance_, a, regime, mode_);
  if (fault_ != ContactFault::none) {
    s.fault = fault_;
    s.fault_message = fault_message_;
  }
  return s;
}

SampleAnalysis analyse_sample(const Model& model, ContactMode mode, const StateVector& y,
                              const StationaryGeometry& geometry) {
  Dynamics dynamics;  // the reduced model's snapshot reads the sleeping state, never the dynamics (make_snapshot)
  if (model.kind == ModelKind::full) evaluate_dynamics(model, mode, y, dynamics);
  return analyse_sample(model, y, geometry, dynamics, mechanical_energy(model, y));
}

SampleAnalysis analyse_sample(const Model& model, const StateVector& y, const StationaryGeometry& geometry,
                              const Dynamics& dynamics, double energy) {
  count(work_counters().sample_analyses);
  SampleAnalysis a = analysis_of(model, y, dynamics, energy, geometry.state);
  a.stationary = stationary_state(model, geometry, shell_spin(y));  // and the sleeping state at this spin
  return a;
}

Snapshot make_snapshot(const Model& model, const StateVector& y, double t, const EnergyBalance& balance,
                       const SampleAnalysis& analysis, Regime regime, ContactMode mode) {
  Snapshot s;
  const Dynamics& dyn = analysis.dynamics;
  const StationaryState& stationary = analysis.stationary;
  const Top& top = model.top;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d u = velocity3(y);
  const TopPose pose = top_pose(model, y, t);  // the fields tf reads without a sample: one definition
  s.t = pose.t;
  s.alpha = pose.alpha;
  s.contact_mode = mode;
  s.gap = y[idx::gap];
  s.tip_center = pose.tip_center;
  s.com = pose.com;
  s.orientation = pose.orientation;
  s.tip_velocity = u;
  s.com_velocity = u + w.cross(top.com_offset * f_hat);
  s.contact_point = pose.contact_point;
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
    s.slip = mode == ContactMode::rolling ? 0.0 : dyn.contact.slip;
    s.mu = dyn.mu;
    s.normal_force = dyn.normal_force;
    s.drilling_torque = dyn.drilling_torque;  // 0 on a point contact and in flight (evaluate_dynamics, motion)
    s.patch_radius = dyn.patch_radius;
    s.friction_force = dyn.friction_force;
    s.com_acceleration = dyn.a_cm;
  }
  s.phi = travel_angle(u.x(), u.y());
  s.has_stationary_state = stationary.exists && stationary.phi_defined;
  s.phi_star = s.has_stationary_state ? stationary.phi : 0.0;
  s.indicators = analysis.indicators;
  s.fault = ContactFault::none;
  if (model.kind == ModelKind::full) {
    if (dyn.margins.painleve <= 0.0) s.fault = ContactFault::painleve;
    else if (dyn.margins.tilt < 0.0) s.fault = ContactFault::fallen;
  }
  s.regime = regime;
  s.energy = analysis.energy;
  s.dissipated_work = y[idx::w_diss];
  s.energy_balance_residual = balance.residual(analysis.energy, y);  // the analysis' energy is y's
  return s;
}

}  // namespace top_sim
