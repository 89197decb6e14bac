// Event location: the first instant on a step's dense output at which a contact event fires (physics.md section 9).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "simulator_impl.hpp"
#include "top_sim/format.hpp"
#include "shape_motion.hpp"

namespace top_sim {

namespace {

// Samples per nutation period where a margin is near its threshold (physics.md section 9: the shortest sign dips,
// e.g. the 34 us of negative N in the first 76 us hop at 5000 rad/s, last about 1/20 of a nutation period).
constexpr double kSamplesPerNutation = 40.0;
constexpr int kMaxSamplesPerStep = 4096;
constexpr int kMinFlightSamples = 4;  // a whole hop may fit in one step: always look inside it
// Guard bands: a margin this close to its threshold at either end of a step makes the step sampled inside.
constexpr double kForceGuard = 0.5;     // N, F_n, rolling margin: fraction of the weight m g
constexpr double kStickGuard = 1.0e3;   // stick function: |v_t| < 1000 v_stick
constexpr double kPainleveGuard = 0.5;  // m n.K d (1 without friction)
constexpr double kEndGuard = 0.05;      // the end margin (e.g. n . f_hat - cos(theta_max))
constexpr double kTouchGuard = 0.1;     // a free shape's gap: fraction of the touching shape's reach

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
  if (m.touch < ModeMargins::kNone) {  // a body with shapes: near a second shape's touchdown
    const ContactShape& k = model.shapes.shape[model.shapes.touching];
    if (m.touch < kTouchGuard * (std::abs(k.offset) + k.radius)) return true;
  }
  return m.lift < kForceGuard * weight || m.transfer < transfer_guard || m.painleve < kPainleveGuard ||
         m.end < kEndGuard;
}

}  // namespace

ModeMargins margins_of(const Model& model, ContactMode mode, const StateVector& y, double cos_max_tilt) {
  Dynamics dyn;
  evaluate_dynamics(model, mode, y, dyn, cos_max_tilt);
  return dyn.margins;
}

// The state at t_end on the step's dense output, and its energy, into scan_end_ (valid once the scan of a tick's
// end has completed).
inline const StateVector& SimulatorImpl::begin_scan(double t_end) {
  scan_end_.valid = false;
  scan_end_.t = t_end;
  if (t_end < stepper_->time()) stepper_->state_at(t_end, scan_end_.y); else scan_end_.y = stepper_->state();
  scan_end_.energy = mechanical_energy(model_, scan_end_.y);
  return scan_end_.y;
}

// An unstable step's events would be fiction: a drift of the energy balance over the scene's limit stops the run.
inline bool SimulatorImpl::energy_balance_holds(const StateVector& y1) {
  const double residual = balance_.residual(scan_end_.energy, y1);
  max_energy_residual_seen_ = std::max(max_energy_residual_seen_, residual);
  if (residual <= energy_residual_limit_) return true;
  stop_unstable_step(residual);
  return false;
}

void SimulatorImpl::stop_unstable_step(double residual) {
  stop_at_step_start(" (the energy balance drifted by " + format_number(residual) + " of the energy scale, over " +
                     "integrator.max_energy_residual = " + format_number(scene_.integrator.max_energy_residual) +
                     ": the step is unstable)");
}

// The first event in (scanned_, t_end]: samples spaced by the nutation period near a threshold, then bisection.
// A quiet scan moves scanned_ to t_end and arms the margins that became positive.
inline LocatedEvent SimulatorImpl::locate_event(double t_end, const StateVector& y1) {
  const double t0 = scanned_;
  const ModeMargins m1 = step_end_margins(y1);
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
    const ModeMargins mk = k == samples ? m1 : margins_of(model_, mode_, yk, cos_max_tilt_);
    const Event kind = sample_event(mk, yk);
    if (kind != Event::none) return {kind, 0, first_event_time(t_prev, tk), mk};
    if (mk.lift > 0.0) lift_armed_ = true;
    if (mk.transfer > 0.0) transfer_armed_ = true;
    if (mk.touch > 0.0) touch_armed_ = true;
    t_prev = tk;
  }
  last_margins_ = m1;
  scanned_ = t_end;
  scan_end_.valid = t_end < stepper_->time();  // a tick's end: its state and sample may read this scan's
  return {};
}

// Scans the current step's dense output from scanned_ to t_end. True when it is clear to t_end; otherwise the
// state is committed at the located event (or fault), the event applied and the stepper restarted.
bool SimulatorImpl::scan_step(double t_end) {
  const StateVector& y1 = begin_scan(t_end);
  if (!energy_balance_holds(y1)) return false;
  if (closed_flight_) return scan_flight(t_end, y1);
  if (model_.kind != ModelKind::full) return scan_reduced(t_end, y1);
  const LocatedEvent e = locate_event(t_end, y1);
  run_cadence(e.kind == Event::none ? t_end : e.t);  // the regime's points up to the event, on this dense output
  if (stopped() || (handover_due_ && take_handover())) return false;
  if (e.kind == Event::none) return true;
  StateVector y;
  stepper_->state_at(e.t, y);
  commit(y, e.t);
  const ModeMargins m = margins_of(model_, mode_, y_, cos_max_tilt_);
  const Event at_event = sample_event(m, y_);
  apply_event(at_event != Event::none ? at_event : e.kind, m);  // rounding at the boundary: the sample's verdict
  return false;
}

// Bisects between the last quiet sample and the first that shows an event for the first instant one fires.
double SimulatorImpl::first_event_time(double lo, double hi) {
  StateVector ym;
  for (int i = 0; i < 80 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    stepper_->state_at(mid, ym);
    if (sample_event(margins_of(model_, mode_, ym, cos_max_tilt_), ym) != Event::none) hi = mid; else lo = mid;
  }
  return hi;
}

// The margins at a step's end: dopri5 (first same as last) has just evaluated the right-hand side there, so
// its recorded contact force serves when y is the stepper's state in every bit (else one full evaluation, staged
// in the sample's slot for the sample of that state).
ModeMargins SimulatorImpl::step_end_margins(const StateVector& y) {
  ModeMargins m;
  sample_.staged = false;
  if (stepper_->state_was_last_rhs() && std::memcmp(y.data(), stepper_->state().data(), sizeof(StateVector)) == 0 &&
      margins_from_record(model_, mode_, y, record_, cos_max_tilt_, m))
    return m;
  Dynamics& staged = sample_.stage();
  evaluate_dynamics(model_, mode_, y, staged, cos_max_tilt_);
  return staged.margins;
}

// Which event a sample shows: faults, then lift-off / touchdown, then stick / slip (armed margins only). The
// margins are the body's one contact shape's; a body of several shapes would take the first shape that shows one.
Event SimulatorImpl::sample_event(const ModeMargins& m, const StateVector& y) const {
  if (model_.kind != ModelKind::full) return Event::none;
  if (m.painleve <= 0.0) return Event::painleve;
  if (mode_ == ContactMode::flight) {
    // Touchdown: the gap is down to 0 while closing; a flight starts at gap 0 with a non-negative rate. A body of
    // shapes touches down with whichever shape's gap reaches 0 first (the lift margin is the least gap).
    if (has_shapes(model_)) [[unlikely]] {
      if (m.lift <= 0.0 && shape_gap_rate(model_, y, model_.shapes.shape[lowest_shape(model_, y)]) < 0.0)
        return Event::touchdown;
    } else if (y[idx::gap] <= 0.0 && y[idx::gap_rate] < 0.0) {
      return Event::touchdown;
    }
  } else if (lift_armed_ && m.lift < 0.0) {
    return Event::lift_off;
  } else if (touch_armed_ && m.touch <= 0.0 && free_shape_gap_rate(model_, y) < 0.0) {
    return Event::second_touchdown;  // a shape reaching the plane closes on it (as a flight's touchdown)
  }
  if (transfer_armed_ && m.transfer <= 0.0) return Event::transfer;
  if (m.end < 0.0) return Event::end;
  return Event::none;
}

// A closed-form step ends at the touchdown it located (the only event of a flight) or short of it.
bool SimulatorImpl::scan_flight(double t_end, const StateVector& y1) {
  scanned_ = t_end;
  run_cadence(t_end);
  if (stopped()) return false;
  if (!(t_end == stepper_->time() && static_cast<const FlightStepper&>(*stepper_).at_touchdown())) return true;
  commit(y1, t_end);
  apply_event(Event::touchdown, margins_of(model_, mode_, y_, cos_max_tilt_));
  return false;
}

}  // namespace top_sim
