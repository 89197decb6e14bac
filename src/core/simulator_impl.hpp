// The Simulator's stages and the data each fills (internal; include/top_sim/simulator.hpp is what a user calls).
//
// One pass of advance_to (simulator.cpp) runs the stages in this order, each in the file named after it:
//   command_queue.cpp      the commands and scene events due, applied at a step boundary
//   (the stepper)          one step of the numeric solution, or of the closed-form flight
//   event_location.cpp     the first event on the step's dense output, located by bisection
//   regime_clock.cpp       the regime's points up to that instant (and auto's handover, auto_handover.cpp)
//   event_application.cpp the event applied: a mode switch, an impact or a fault
//   sample_stage.cpp       what a reader sees: the sample of the committed state, analysed on the first read
// commit() is the one place a new state and time take effect, and so the one place derived values go stale.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sample.hpp"
#include "auto_model.hpp"
#include "top_sim/command.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/dynamics.hpp"
#include "energy.hpp"
#include "flight.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// What one sample of the dense output shows; when several show at once, the first in this order is handled.
enum class Event { none, painleve, lift_off, touchdown, second_touchdown, transfer, end };  // end: the tilt slot's end state

// The first instant in a step at which an event fires, as event_location.cpp found it: what fired, on which of
// the body's contact shapes (one today, the tip sphere: index 0), and the margins of the sample that showed it.
struct LocatedEvent {
  Event kind = Event::none;
  std::size_t shape = 0;
  double t = 0.0;
  ModeMargins sample_margins;
};

// The margins of every contact shape at y in `mode` (one full dynamics evaluation).
ModeMargins margins_of(const Model& model, ContactMode mode, const StateVector& y, double cos_max_tilt);

// A call's wall-clock budget: it ends a pass at the first step boundary after its deadline.
struct StepBudget {
  bool limited = false;
  std::chrono::steady_clock::time_point start, deadline;
  double t_entry = 0.0;
  bool worked = false;  // a step or an event since `start`: before one, the clock still reads about `start`
};

class SimulatorImpl {
 public:
  explicit SimulatorImpl(const Scene& scene);
  SimulatorImpl(const SimulatorImpl&) = delete;  // the steppers call back into this object
  SimulatorImpl& operator=(const SimulatorImpl&) = delete;

  bool advance_to(double t, double budget_seconds, std::chrono::steady_clock::time_point start);
  std::string submit(const Command& command);
  void reset();
  Snapshot snapshot() const;
  const SampleAnalysis& sample() const;
  std::array<double, kContactModeCount> mode_seconds() const;
  std::vector<ModeSwitch> take_mode_switches();
  std::array<double, kRegimeCount> regime_seconds() const;
  double reduced_seconds() const;
  const Stepper& numeric_stepper() const { return closed_flight_ ? *parked_ : *stepper_; }

  // ---- What every advance touches, first and together. A node advances thousands of tops per tick, and the cache
  // lines a top touches are what its tick costs beyond the arithmetic: with these fields spread over their stages'
  // groups below, 1000 default tops took 57.7 D1 misses per top and tick, 56.3 with them here (cachegrind as in
  // bench/tick_footprint.cpp's header; 8,747 instructions either way).
  StateVector y_{};             // the state: committed by commit() alone
  double t_ = 0.0;
  std::uint64_t revision_ = 0;  // counts commits: a derived value made at another revision is stale
  double next_event_t_ = 0.0;   // command queue: t_origin_ + the next scripted event's t (infinite when none is left)
  double t_origin_ = 0.0;       // time of the last reset: scripted events and the regime clock are relative to it
  double scanned_ = 0.0;        // event location: the current step is scanned up to here
  std::unique_ptr<Stepper> stepper_;
  ContactFault fault_ = ContactFault::none;  // the first fault stops the run; time() stays at it
  EndState end_state_ = EndState::none;      // a named end (a disc lying flat) stops it too, not as a fault
  ContactMode mode_ = ContactMode::slipping;
  ContactModel contact_model_ = ContactModel::point;  // contact_model(model_), set at each restart
  bool closed_flight_ = false;                        // stepper_ is the closed-form flight
  bool lift_armed_ = false, transfer_armed_ = false;  // the margin has been > 0 since the mode began
  bool touch_armed_ = false;                          // a shape not touching has had a gap > 0 since
  bool layer_kink_at_rest_ = false;  // the slip-onset layer (set at each restart): mu(0) > 0, and its half width
  bool handover_due_ = false;        // auto: a handover found at a regime point, taken by the scan that ran the clock
  std::atomic<bool> has_pending_{false};  // pending_ is not empty (set under the lock; read without it)
  double layer_width_ = 0.0;
  double cos_max_tilt_ = 1.0;
  double energy_residual_limit_ = 0.0;     // the scene's integrator.max_energy_residual
  double max_energy_residual_seen_ = 0.0;  // since the last reset
  double cadence_t_ = 0.0;                 // regime clock: the last point's time and index
  std::uint64_t cadence_k_ = 0;
  EnergyBalance balance_;
  ModeMargins last_margins_;   // at scanned_
  ContactForceRecord record_;  // the contact force of the last right-hand side (at stepper_'s state if it says so)
  // The model in force: the scene's, as changed by the commands applied since the last reset (every right-hand
  // side reads it).
  Model model_;

  // ---- The rest, grouped by the stage that fills it.
  std::string fault_message_;
  std::string end_message_;
  // Solved at reset and commands (no spin): the regime clock reads its existence and unstable root, a sample adds
  // omega* and u* at its spin.
  StationaryGeometry stationary_geometry_;
  std::unique_ptr<Stepper> parked_ = std::make_unique<FlightStepper>(model_);  // the stepper not in use

  // command_queue.cpp: commands from any thread, and the scene's scripted events.
  std::vector<Command> pending_;
  mutable std::mutex pending_mutex_;  // guards pending_, and the owner's writes to model_ (submit() reads it)
  std::string stopped_refusal_;      // why submit() refuses after an end or a fault; empty while running
  std::size_t next_event_ = 0;

  // event_location.cpp: the end of the last scan when it fell inside a step (a tick's end): its state and energy
  // (and its dynamics, staged in the sample's slot below). The tick's state and its sample read them instead of
  // evaluating the same state again. Valid until the stepper restarts (every change of state, model or mode).
  struct ScanEnd {
    bool valid = false;
    double t = 0.0;
    double energy = 0.0;
    StateVector y{};
  };
  ScanEnd scan_end_;

  // event_application.cpp: the contact mode's history and the Zeno guard.
  double mode_since_ = 0.0;
  std::array<double, kContactModeCount> mode_seconds_{};
  std::vector<ModeSwitch> switches_;
  std::uint64_t switch_count_ = 0;
  int instant_switches_ = 0;  // consecutive switches without time advancing (Zeno guard)
  int clustered_switches_ = 0;  // consecutive switches each within 1 us of the last (clustering guard)
  double last_switch_t_ = -1.0;

  // regime_clock.cpp: the last point's regime (the hysteresis of classify()), and the seconds in each regime.
  Regime cadence_regime_ = Regime::nutating;
  std::array<double, kRegimeCount> regime_seconds_{};

  // auto_handover.cpp (model.kind auto): the reduction last analysed, the handover found (handover_due_ above),
  // and the bookkeeping of the reduced model's time.
  Reduction reduction_;
  struct PendingHandover {
    double t = 0.0;
    double energy_loss = 0.0;  // E before - E after: booked in W_diss
    StateVector y{};
  };
  PendingHandover handover_;
  std::uint64_t handovers_ = 0;
  double reduced_since_ = 0.0;
  double reduced_seconds_ = 0.0;

  // sample.cpp: the lazy sample of the committed state, made at `revision` and classified at regime point `point`.
  // A scan whose step-end margins take a full evaluation evaluates into the analysis' dynamics (stage()): that is
  // the tick's end, the state the tick commits and its reader reads. A copy from a slot of the scan's own cost 1000
  // default tops 6 more D1 misses per top and tick (56.3 against 50.3 staged here, 48.9 at 591c51d before the
  // stages; cachegrind, tick_footprint).
  struct SampleCache {
    static constexpr std::uint64_t kStale = ~std::uint64_t{0};
    std::uint64_t revision = kStale;
    std::uint64_t point = 0;
    bool staged = false;  // analysis.dynamics holds the dynamics of scan_end_.y, not of an analysed state
    SampleAnalysis analysis;
    Regime regime = Regime::nutating;
    Dynamics& stage() {
      revision = kStale;  // the analysis it overwrites is no longer whole
      staged = true;
      return analysis.dynamics;
    }
  };
  mutable SampleCache sample_;

  // The scene (read at resets, scripted events and faults only: last, away from what every step touches).
  Scene scene_;

  // simulator.cpp: the driver and the one commit.
  void commit(const StateVector& y, double t);
  void restart(const StateVector& y, double t, bool rebase_energy);
  void fail(ContactFault fault, const std::string& message);
  void end(EndState state, double margin);  // stops the run at a named end state (message in end_message_)
  void refuse_commands(const std::string& why);  // from now on submit() answers why
  bool stopped() const { return fault_ != ContactFault::none || end_state_ != EndState::none; }
  void stop_at_step_start(const std::string& detail);
  enum class Reach { stop, fault, out_of_budget };
  Reach step_to(double t_stop, StepBudget& budget);
  void commit_stop(double t_stop);
  bool in_stiff_layer(const StateVector& y, bool inside) const;
  // command_queue.cpp
  bool scene_event_due() const { return next_event_t_ <= t_; }
  void schedule_next_event();
  void apply_pending();
  void reclose_contact(StateVector& y);
  // event_location.cpp
  bool scan_step(double t_end);
  const StateVector& begin_scan(double t_end);
  bool energy_balance_holds(const StateVector& y1);
  void stop_unstable_step(double residual);
  LocatedEvent locate_event(double t_end, const StateVector& y1);
  ModeMargins step_end_margins(const StateVector& y);
  Event sample_event(const ModeMargins& m, const StateVector& y) const;
  bool scan_flight(double t_end, const StateVector& y1);
  double first_event_time(double lo, double hi);
  // event_application.cpp
  void apply_event(Event event, const ModeMargins& m);
  void switch_mode(ContactMode mode, ModeSwitchKind kind, double energy_change = 0.0);
  void touchdown(StateVector& y);
  void second_touchdown(StateVector& y);
  bool pair_transfer(StateVector& y);
  ContactMode pair_mode() const;
  bool stick_pair_contact(StateVector& y, int k);
  void stick_pair_contacts(StateVector& y);
  void let_go_of_one(StateVector& y);
  void settle_pair(StateVector& y);
  void select_stepper();
  // regime_clock.cpp
  void run_cadence(double t_end);
  void cadence_point(double t, const StateVector& y);
  void skip_cadence(double t_end);
  // auto_handover.cpp
  void consider_handover(double t, const StateVector& y);
  bool take_handover();
  bool scan_reduced(double t_end, const StateVector& y1);
  void resume_full(double t);
};

}  // namespace top_sim
