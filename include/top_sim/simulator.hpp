// Owns time, the steppers, the contact mode, scripted events and pending commands; advances one top.
//
// Threading contract: one thread owns a Simulator and calls everything but submit(); submit() may be called from
// any thread: commands enter through one locked queue and are applied at the next step boundary. submit()
// validates against the model in force, which the owning thread changes (reset, applying commands) only under
// that queue's lock; the owner's own reads need no lock. Not copyable: the steppers call back into the object.
#pragma once

#include <array>
#include <chrono>
#include <limits>
#include <memory>
#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include "top_sim/auto_model.hpp"
#include "top_sim/command.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/dynamics.hpp"
#include "top_sim/energy.hpp"
#include "top_sim/flight.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/pose.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// What one sample derives from a state, each once: the dynamics in the contact mode, the sleeping state at the
// state's shell spin, and the regime indicators (zero for the adiabatic model) that the classification reads.
struct SampleAnalysis {
  Dynamics dynamics;
  StationaryState stationary;
  RegimeIndicators indicators;
  double energy = 0.0;  // mechanical energy E [J]
};

// `geometry`: the model's stationary_geometry(), solved once per model change.
SampleAnalysis analyse_sample(const Model& model, ContactMode mode, const StateVector& y,
                              const StationaryGeometry& geometry);
// The same, from y's dynamics (evaluate_dynamics in `mode`) and energy evaluated already.
SampleAnalysis analyse_sample(const Model& model, const StateVector& y, const StationaryGeometry& geometry,
                              const Dynamics& dynamics, double energy);

class Simulator {
 public:
  explicit Simulator(const Scene& scene);
  Simulator(const Simulator&) = delete;  // the steppers call back into this object
  Simulator& operator=(const Simulator&) = delete;

  // Integrates to simulated time t (>= time()); applies due events and pending commands at step boundaries;
  // switches contact modes at located events; stops at a contact fault (time() then stays at the fault).
  // With a finite budget (wall-clock seconds) it returns after the first step or event that exhausts it: false when
  // it stopped short of t (time() < t, no fault), true otherwise. The state is always a consistent step boundary.
  bool advance_to(double t, double budget_seconds = std::numeric_limits<double>::infinity());
  // The same with the budget counted from `start`, a steady_clock reading the caller has just taken (the node reads
  // the clock once per top for its share of the tick's budget and for this; a clock read is 3 % of its tick).
  bool advance_to(double t, double budget_seconds, std::chrono::steady_clock::time_point start);

  // Validates and queues a command for the next step boundary; returns "" or the error message. Any thread.
  // The command is checked against the model in force now, not against the effect of commands still queued.
  std::string submit(const Command& command);

  // Back to the scene's initial state; time keeps running forward (scripted events restart).
  void reset();

  double time() const { return t_; }
  const StateVector& state() const { return y_; }
  // The model in force: the scene's, as changed by the commands applied since the last reset.
  const Model& model() const { return model_; }
  const Scene& scene() const { return scene_; }
  // Every derived quantity of the current state. Advancing builds no sample: the first read after a change of the
  // state, time, model or mode analyses it (one dynamics evaluation, one stationary solve, the indicators, the
  // energy) and caches it; the regime is that state's classification with the hysteresis of the last regime
  // cadence point (never committed by a read).
  Snapshot snapshot() const;
  // The snapshot's placing fields alone (tf, trails): no analysis, so reading it every tick costs no sample.
  TopPose pose() const { return top_pose(model_, y_, t_); }
  const StepperStats& stats() const { return numeric_stepper().stats; }
  ContactFault fault() const { return fault_; }
  const std::string& fault_message() const { return fault_message_; }
  // The analytic sleeping state for the current alpha and shell spin (solved on the first read, then cached).
  const StationaryState& stationary() const { return sample().stationary; }
  double max_energy_residual() const { return max_energy_residual_seen_; }

  ContactMode contact_mode() const { return mode_; }
  // Simulated seconds spent in each contact mode since the last reset (index: ContactMode).
  std::array<double, kContactModeCount> mode_seconds() const;
  // Mode switches since the last call, in time order (the caller keeps them if it needs the history). At most
  // kMaxPendingSwitches are held; mode_switch_count() counts all since the reset.
  std::vector<ModeSwitch> take_mode_switches();
  std::uint64_t mode_switch_count() const { return switch_count_; }
  // Simulated seconds in each regime since the last reset (index: Regime), classified on the regime cadence: each
  // interval [t_k, t_k+1) counts for the regime at t_k, so the shares depend on no reader and on no slicing.
  std::array<double, kRegimeCount> regime_seconds() const;
  // The regime's own clock: classified at t_reset + k kRegimeCadence on the dense output, whoever reads. 0.1 s
  // resolves the regimes' changes (nutation dies in seconds, precession in tens: physics.md section 10) for one
  // dynamics evaluation, the indicators and the energy per point (no stationary solve, no sample).
  static constexpr double kRegimeCadence = 0.1;
  static constexpr std::size_t kMaxPendingSwitches = 100000;
  // model.kind auto (physics.md section 7.1): handovers to the reduced model since the last reset, and the
  // simulated seconds spent in it.
  std::uint64_t handovers() const { return handovers_; }
  double reduced_seconds() const;
  // Steps made by rosenbrock4 across the stiff slip-onset layer (included in stats()).
  std::uint64_t layer_steps() const { return numeric_stepper().layer_steps(); }

 private:
  void restart_stepper(bool rebase_energy);
  void apply_pending();
  bool scene_event_due() const;  // the scene's next event is at or before t_
  void schedule_next_event();    // next_event_t_ from next_event_ and t_origin_
  bool scan_events(double t_end);
  const StateVector& begin_scan(double t_end);
  bool scan_flight(double t_end, const StateVector& y1);
  void select_stepper();
  const Stepper& numeric_stepper() const { return closed_flight_ ? *parked_ : *stepper_; }
  ModeMargins step_end_margins(const StateVector& y, Dynamics& evaluated, bool& has_evaluated);
  enum class Event;  // what a sample shows (simulator.cpp)
  Event sample_event(const ModeMargins& m, const StateVector& y) const;
  void handle_event(Event event, const ModeMargins& m);
  void switch_mode(ContactMode mode, ModeSwitchKind kind, double energy_change = 0.0);
  void reclose_contact();
  void fail(ContactFault fault, const std::string& message);
  void stop_at_step_start(const std::string& detail);
  const SampleAnalysis& sample() const;
  void invalidate_sample() { sample_valid_ = false; }
  void run_cadence(double t_end);
  void cadence_point(double t, const StateVector& y);
  bool in_stiff_layer(const StateVector& y, bool inside) const;
  void consider_handover(double t, const StateVector& y);
  bool take_handover();
  bool scan_reduced(double t_end, const StateVector& y1);
  void skip_cadence(double t_end);
  void resume_full();

  // What every advance and event scan reads or writes comes first, in a few cache lines: a node advances a
  // thousand tops per tick, and the lines a top touches are what its tick costs beyond the arithmetic.
  StateVector y_{};
  double t_ = 0.0;
  double t_origin_ = 0.0;              // time of the last reset: scripted events are relative to it
  double scanned_ = 0.0;               // the current step's dense output is scanned for events up to here
  double next_event_t_ = 0.0;          // t_origin_ + the next scripted event's t (infinite when none is left)
  double energy_residual_limit_ = 0.0;  // the scene's integrator.max_energy_residual
  std::unique_ptr<Stepper> stepper_;
  std::size_t next_event_ = 0;
  ContactFault fault_ = ContactFault::none;
  ContactMode mode_ = ContactMode::slipping;
  bool closed_flight_ = false;  // stepper_ is the closed-form flight
  ContactModel contact_model_ = ContactModel::point;  // contact_model(model_), set at each restart
  bool lift_armed_ = false, transfer_armed_ = false;  // the margin has been > 0 since the mode began
  // The slip-onset layer of the current model (set at each restart): its half width in |v_t| and whether mu(0) > 0.
  bool layer_kink_at_rest_ = false;
  std::atomic<bool> has_pending_{false};  // pending_ is not empty (set under the lock; read without it)
  mutable bool sample_valid_ = false;
  double layer_width_ = 0.0;
  double cos_max_tilt_ = 1.0;
  EnergyBalance balance_;
  double max_energy_residual_seen_ = 0.0;  // since the last reset
  ModeMargins last_margins_;          // at scanned_
  ContactForceRecord record_;         // the contact force of the last right-hand side (at stepper_'s state if it says so)
  // The regime cadence: the last point's time, index and regime (the hysteresis of classify()), and the seconds.
  double cadence_t_ = 0.0;
  std::uint64_t cadence_k_ = 0;
  Regime cadence_regime_ = Regime::nutating;
  // The end of the last event scan when it fell inside a step (a tick's end): its state and energy, and whether
  // the margins took a full evaluation there (left in sample_.dynamics, which the sample of that state would
  // write: no other cache lines per top). The tick's state and its sample read them instead of evaluating the
  // same state again. Valid until the stepper restarts (every change of state, model or mode).
  struct ScanEnd {
    bool valid = false;
    bool has_dynamics = false;
    double t = 0.0;
    double energy = 0.0;
    StateVector y{};
  };
  ScanEnd scan_end_;
  Model model_;
  // The lazy sample of (y_, t_, model_, mode_): valid until one of them changes (single owning thread).
  mutable SampleAnalysis sample_;
  mutable Regime sample_regime_ = Regime::nutating;
  // Solved at reset and commands (no spin): the cadence reads its existence and unstable root, a sample adds
  // omega* and u* at its spin.
  StationaryGeometry stationary_geometry_;

  // Read at resets, commands, events and faults.
  Scene scene_;
  // model.kind auto: the reduction last analysed, a handover found at a cadence point (taken by the scan that ran
  // the cadence), and the bookkeeping of the reduced model's time.
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
  // The stepper not in use: the closed-form flight (flight.hpp) while stepping, the numeric one in such a flight.
  std::unique_ptr<Stepper> parked_ = std::make_unique<FlightStepper>(model_);
  std::vector<Command> pending_;
  mutable std::mutex pending_mutex_;  // guards pending_, and the owner's writes to model_ (submit() reads it)
  std::string fault_message_;
  std::array<double, kRegimeCount> regime_seconds_{};
  double mode_since_ = 0.0;
  std::array<double, kContactModeCount> mode_seconds_{};
  std::vector<ModeSwitch> switches_;
  std::uint64_t switch_count_ = 0;
  int instant_switches_ = 0;          // consecutive switches without time advancing (Zeno guard)
  double last_switch_t_ = -1.0;
};

// Snapshot of a state of a model from its analysis and its regime (classified by the caller, with hysteresis).
Snapshot make_snapshot(const Model& model, const StateVector& y, double t, const EnergyBalance& balance,
                       const SampleAnalysis& analysis, Regime regime, ContactMode mode = ContactMode::slipping);

}  // namespace top_sim
