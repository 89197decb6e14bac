// The Simulator's stages and the data each fills (internal; include/top_sim/simulator.hpp is what a user calls).
//
// One pass of advance_to (simulator.cpp) runs the stages in this order, each in the file named after it:
//   command_queue.cpp      the commands and scene events due, applied at a step boundary
//   (the stepper)          one step of the numeric solution, or of the closed-form flight
//   event_location.cpp     the first event on the step's dense output, located by bisection
//   regime_clock.cpp       the regime's points up to that instant (and auto's handover, auto_handover.cpp)
//   event_application.cpp the event applied: a mode switch, an impact or a fault
//   sample.cpp             what a reader sees: the sample of the committed state, analysed on the first read
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
#include "top_sim/auto_model.hpp"
#include "top_sim/command.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/energy.hpp"
#include "top_sim/flight.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// What one sample of the dense output shows; when several show at once, the first in this order is handled.
enum class Event { none, painleve, lift_off, touchdown, transfer, fallen };

// The first instant in a step at which an event fires, as event_location.cpp found it: what fired, on which of
// the body's contact shapes (one today, the tip sphere: index 0), and the margins of the sample that showed it.
struct LocatedEvent {
  Event kind = Event::none;
  std::size_t shape = 0;
  double t = 0.0;
  ModeMargins sample_margins;
};

// The margins of every contact shape at y in `mode` (one full dynamics evaluation).
ModeMargins margins_of(const Model& model, ContactMode mode, const StateVector& y);

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

  // The state: committed by commit() alone.
  StateVector y_{};
  double t_ = 0.0;
  std::uint64_t revision_ = 0;  // counts commits: a derived value made at another revision is stale

  // Faults: the first one stops the run; time() stays at it.
  ContactFault fault_ = ContactFault::none;
  std::string fault_message_;

  // The model in force: the scene's, as changed by the commands applied since the last reset.
  Model model_;
  ContactModel contact_model_ = ContactModel::point;  // contact_model(model_), set at each restart
  // Solved at reset and commands (no spin): the regime clock reads its existence and unstable root, a sample adds
  // omega* and u* at its spin.
  StationaryGeometry stationary_geometry_;

  // The stepper, and the stepper not in use: the closed-form flight (flight.hpp) while stepping, the numeric one
  // in such a flight.
  std::unique_ptr<Stepper> stepper_;
  std::unique_ptr<Stepper> parked_ = std::make_unique<FlightStepper>(model_);
  bool closed_flight_ = false;  // stepper_ is the closed-form flight
  ContactForceRecord record_;   // the contact force of the last right-hand side (at stepper_'s state if it says so)
  // The slip-onset layer of the current model (set at each restart): its half width in |v_t| and whether mu(0) > 0.
  double layer_width_ = 0.0;
  bool layer_kink_at_rest_ = false;
  double cos_max_tilt_ = 1.0;
  EnergyBalance balance_;
  double energy_residual_limit_ = 0.0;    // the scene's integrator.max_energy_residual
  double max_energy_residual_seen_ = 0.0;  // since the last reset

  // command_queue.cpp: commands from any thread, and the scene's scripted events.
  std::vector<Command> pending_;
  mutable std::mutex pending_mutex_;       // guards pending_, and the owner's writes to model_ (submit() reads it)
  std::atomic<bool> has_pending_{false};  // pending_ is not empty (set under the lock; read without it)
  double t_origin_ = 0.0;                 // time of the last reset: scripted events are relative to it
  std::size_t next_event_ = 0;
  double next_event_t_ = 0.0;  // t_origin_ + the next scripted event's t (infinite when none is left)

  // event_location.cpp: how far the current step is scanned, the margins there, and which events are armed.
  double scanned_ = 0.0;
  ModeMargins last_margins_;                          // at scanned_
  bool lift_armed_ = false, transfer_armed_ = false;  // the margin has been > 0 since the mode began
  // The end of the last scan when it fell inside a step (a tick's end): its state and energy, and the dynamics
  // when its margins took a full evaluation. The tick's state and its sample read them instead of evaluating the
  // same state again. Valid until the stepper restarts (every change of state, model or mode).
  struct ScanEnd {
    bool valid = false;
    bool has_dynamics = false;
    double t = 0.0;
    double energy = 0.0;
    StateVector y{};
    Dynamics dynamics;
  };
  ScanEnd scan_end_;

  // event_application.cpp: the contact mode, its history and the Zeno guard.
  ContactMode mode_ = ContactMode::slipping;
  double mode_since_ = 0.0;
  std::array<double, kContactModeCount> mode_seconds_{};
  std::vector<ModeSwitch> switches_;
  std::uint64_t switch_count_ = 0;
  int instant_switches_ = 0;  // consecutive switches without time advancing (Zeno guard)
  double last_switch_t_ = -1.0;

  // regime_clock.cpp: the last point's time, index and regime (the hysteresis of classify()), and the seconds.
  double cadence_t_ = 0.0;
  std::uint64_t cadence_k_ = 0;
  Regime cadence_regime_ = Regime::nutating;
  std::array<double, kRegimeCount> regime_seconds_{};

  // auto_handover.cpp (model.kind auto): the reduction last analysed, a handover found at a regime point (taken by
  // the scan that ran the clock), and the bookkeeping of the reduced model's time.
  Reduction reduction_;
  struct PendingHandover {
    bool due = false;
    double t = 0.0;
    double energy_loss = 0.0;  // E before - E after: booked in W_diss
    StateVector y{};
  };
  PendingHandover handover_;
  std::uint64_t handovers_ = 0;
  double reduced_since_ = 0.0;
  double reduced_seconds_ = 0.0;

  // sample.cpp: the lazy sample of the committed state, made at `revision` and classified at regime point `point`.
  struct SampleCache {
    std::uint64_t revision = ~std::uint64_t{0};
    std::uint64_t point = 0;
    SampleAnalysis analysis;
    Regime regime = Regime::nutating;
  };
  mutable SampleCache sample_;

  // The scene (read at resets, scripted events and faults only: last, away from what every step touches).
  Scene scene_;

  // simulator.cpp: the driver and the one commit.
  void commit(const StateVector& y, double t);
  void restart(const StateVector& y, double t, bool rebase_energy);
  void fail(ContactFault fault, const std::string& message);
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
