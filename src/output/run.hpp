// Shared by the command-line tools: run a scene, sample it, summarise the samples (docs/interfaces.md). The CSV and
// JSON writers are in writers.hpp.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>
#include <array>
#include <cstdint>

#include "top_sim/cpu_time.hpp"  // thread_cpu_seconds, which every tool reports
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// What a stream of Snapshots in time order says: top_sim_run's samples, or a bag's TopStates (top_sim_bag).
// Sampled: each interval between two samples counts for the earlier sample's regime and contact mode, and a mode
// change is seen at the first sample in the new mode (switches and returns between two samples are not seen).
struct SampledSummary {
  std::uint64_t samples = 0;
  double t_first = 0.0, t_last = 0.0;
  std::array<double, kRegimeCount> regime_seconds{};     // index: Regime
  std::array<double, kContactModeCount> mode_seconds{};  // index: ContactMode
  std::vector<ModeSwitch> mode_changes;  // kind and energy_change unknown (left at their defaults)
  std::uint64_t mode_change_count = 0;   // all of them (the list stops at Simulator::kMaxPendingSwitches)
  double max_energy_residual = 0.0;      // over the samples
  std::optional<double> phi_measured;    // from the contact point at the mark (interpolated) to the last sample
  Snapshot last;
};

// The start of the last 20 % of [t0, t_end], where phi_measured starts.
double mark_time(double t0, double t_end);

// phi_measured: direction of travel of the contact point from `mark` to `last`; none after a contact fault
// (TopState gives only its text: a fault message counts) or without displacement.
std::optional<double> travel_since(const Eigen::Vector2d& mark, const Snapshot& last);

class SummaryAccumulator {
 public:
  // t_mark: mark_time() of the stream's first and last sample times.
  explicit SummaryAccumulator(double t_mark) : t_mark_(t_mark) {}
  // Samples must come in increasing time.
  void add(const Snapshot& s);
  SampledSummary result() const;
  double t_last() const { return sum_.t_last; }

 private:
  double t_mark_;
  std::optional<Eigen::Vector2d> mark_;
  SampledSummary sum_;
};

// phi_star from the stationary solver's answer: phi*, or empty and why.
void set_phi_star(const StationaryState& st, std::optional<double>& phi_star, std::string& note);

struct RunOptions {
  double duration = 10.0;     // simulated seconds
  double sample_rate = 0.0;   // samples per simulated second (0 = none): RunResult.sampled and on_sample
  std::function<void(const Snapshot&)> on_sample;
  // Called about every progress_interval seconds of wall time during long advances (none when empty).
  std::function<void(double t)> on_progress;
  double progress_interval = 1.0;
};

struct RunResult {
  Snapshot final;
  double sim_seconds = 0.0;
  double cpu_seconds = 0.0;
  StepperStats stats;
  std::optional<double> phi_measured;  // travel direction over the last 20 % of the run
  std::optional<double> phi_star;      // analytic, when a stationary state exists
  std::string stationary_note;         // why phi_star is absent
  double max_energy_residual = 0.0;
  std::vector<ModeSwitch> mode_switches;  // every contact-mode switch of the run, in time order
  std::uint64_t mode_switch_count = 0;    // all of them (the list stops at Simulator::kMaxPendingSwitches)
  std::array<double, kContactModeCount> mode_seconds{};  // simulated seconds in each mode (this run)
  std::array<double, kRegimeCount> regime_seconds{};     // in each regime, on the simulator's regime cadence
  SampledSummary sampled;  // of the samples at RunOptions.sample_rate (with the initial state); none without
  // model.kind auto: handovers to the reduced model and simulated seconds in it since the simulator's reset.
  std::uint64_t handovers = 0;
  double reduced_seconds = 0.0;
};

// Advances the simulator from its current time by options.duration.
RunResult run(Simulator& sim, const RunOptions& options);

// A fault: the core's kind, or (from a TopState, which carries only the text) its message.
inline bool faulted(const Snapshot& s) { return s.fault != ContactFault::none || !s.fault_message.empty(); }

}  // namespace top_sim
