// Owns time, the stepper, scripted events and pending commands; advances one top.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "top_sim/command.hpp"
#include "top_sim/energy.hpp"
#include "top_sim/integrators.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/snapshot.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

class Simulator {
 public:
  explicit Simulator(const Scene& scene);

  // Integrates to simulated time t (>= time()); applies due events and pending commands at step
  // boundaries; stops at a contact fault (time() then stays at the fault).
  void advance_to(double t);

  // Validates and queues a command for the next step boundary; returns "" or the error message.
  std::string submit(const Command& command);

  // Back to the scene's initial state; time keeps running forward (scripted events restart).
  void reset();

  double time() const { return t_; }
  const StateVector& state() const { return y_; }
  const Model& model() const { return model_; }
  const Scene& scene() const { return scene_; }
  Snapshot snapshot() const;
  const StepperStats& stats() const { return stepper_->stats; }
  ContactFault fault() const { return fault_; }
  const std::string& fault_message() const { return fault_message_; }
  // The analytic sleeping state for the current alpha and shell spin.
  StationaryState stationary() const;
  double max_energy_residual() const { return max_residual_; }

 private:
  void restart_stepper();
  void apply_now(const Command& c);
  void apply_pending();
  bool check_last_step();
  void update_regime();

  Scene scene_;
  Model model_;
  std::unique_ptr<Stepper> stepper_;
  StateVector y_{};
  double t_ = 0.0;
  double t_origin_ = 0.0;        // time of the last reset: scripted events are relative to it
  std::size_t next_event_ = 0;
  std::vector<Command> pending_;
  mutable std::mutex pending_mutex_;
  EnergyBalance balance_;
  double max_residual_ = 0.0;
  ContactFault fault_ = ContactFault::none;
  std::string fault_message_;
  ContactMargins last_margins_;
  Regime regime_ = Regime::nutating;  // at the end of the last advance: the hysteresis of classify()
};

// Snapshot of an arbitrary state of a model (used by the Simulator and by tools).
Snapshot make_snapshot(const Model& model, const StateVector& y, double t, const EnergyBalance& balance,
                       const StationaryState& stationary, Regime previous = Regime::nutating);

}  // namespace top_sim
