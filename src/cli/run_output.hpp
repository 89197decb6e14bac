// Shared by the command-line tools: run a scene, sample it, summarise it (docs/interfaces.md).
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>
#include <array>
#include <cstdint>

#include "top_sim/simulator.hpp"

namespace top_sim {

struct RunOptions {
  double duration = 10.0;     // simulated seconds
  double sample_rate = 0.0;   // samples per simulated second for on_sample (0 = none)
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
};

// Advances the simulator from its current time by options.duration.
RunResult run(Simulator& sim, const RunOptions& options);

// CPU seconds of the calling thread (tools run simulations in parallel threads; std::clock counts them all).
double thread_cpu_seconds();

void write_csv_header(std::ostream& os);
void write_csv_row(std::ostream& os, const Snapshot& s);

// The JSON summary of docs/interfaces.md.
std::string summary_json(const Scene& scene, const RunResult& r);

}  // namespace top_sim
