// Owns time, the steppers, the contact mode, scripted events and pending commands; advances one top.
//
// Threading contract: one thread owns a Simulator and calls everything but submit(); submit() may be called from
// any thread: commands enter through one locked queue and are applied at the next step boundary. submit()
// validates against the model in force, which the owning thread changes (reset, applying commands) only under
// that queue's lock; the owner's own reads need no lock. Its stages live in src/core (simulator_impl.hpp).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "top_sim/command.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/pose.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

class SimulatorImpl;

class Simulator {
 public:
  explicit Simulator(const Scene& scene);
  ~Simulator();
  Simulator(const Simulator&) = delete;  // the steppers call back into its stages
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

  double time() const;
  const StateVector& state() const;
  // The model in force: the scene's, as changed by the commands applied since the last reset.
  const Model& model() const;
  const Scene& scene() const;
  // Every derived quantity of the current state. Advancing builds no sample: the first read after a change of the
  // state, time, model or mode analyses it (one dynamics evaluation, one stationary solve, the indicators, the
  // energy) and caches it; the regime is that state's classification with the hysteresis of the last regime
  // cadence point (never committed by a read).
  Snapshot snapshot() const;
  // The snapshot's placing fields alone (tf, trails): no analysis, so reading it every tick costs no sample.
  TopPose pose() const;
  const StepperStats& stats() const;
  ContactFault fault() const;
  // A named end that stopped the run without a fault (physics.md sections 8 and 13); end_message() says it.
  EndState end_state() const;
  // A fault or an end state stopped the run: time() stays there.
  bool stopped() const;
  const std::string& fault_message() const;  // empty unless fault() is set
  const std::string& end_message() const;    // empty unless end_state() is set
  // The analytic sleeping state for the current alpha and shell spin (solved on the first read, then cached).
  const StationaryState& stationary() const;
  double max_energy_residual() const;

  ContactMode contact_mode() const;
  // Simulated seconds spent in each contact mode since the last reset (index: ContactMode).
  std::array<double, kContactModeCount> mode_seconds() const;
  // Mode switches since the last call, in time order (the caller keeps them if it needs the history). At most
  // kMaxPendingSwitches are held; mode_switch_count() counts all since the reset.
  std::vector<ModeSwitch> take_mode_switches();
  std::uint64_t mode_switch_count() const;
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
  std::uint64_t handovers() const;
  double reduced_seconds() const;
  // Steps made by rosenbrock4 across the stiff slip-onset layer (included in stats()).
  std::uint64_t layer_steps() const;

 private:
  std::unique_ptr<SimulatorImpl> impl_;
};

}  // namespace top_sim
