// The command line of a sweep: the grid and how each point runs. Shared by top_sim_sweep and the Python sweep
// (python3 -m top_sim.sweep), so both take the same flags and reject bad ones with the same messages.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sweep_point.hpp"

namespace top_sim {

// The flags of top_sim_sweep, parsed.
struct SweepOptions {
  std::vector<double> alphas, spins = {200.0};
  std::vector<std::string> tops = {"aluminium"}, planes = {"pmma"};
  std::vector<std::optional<double>> mu_cs = {std::nullopt}, s_cs = {std::nullopt};
  std::vector<PatchRadius> patches = {PatchRadius{}};
  SweepSettings settings;
  std::string out_path = "-";
  unsigned threads = 0;  // 0 = all cores
};

// The usage text of the flags above (each adapter prints its own first line and extra flags around it).
extern const char* const kSweepOptionsUsage;

// Reads `args` (flags and values, no program name) into `o`; throws top_sim_cli::BadArgument naming the flag,
// the value and the allowed range. Returns false when it was asked for help (-h, --help).
bool parse_sweep_options(const std::vector<std::string>& args, SweepOptions& o);

// Every combination of the grid's values: top, plane, mu_c, s_c, patch radius, spin outermost to alpha innermost.
std::vector<SweepPoint> make_sweep_grid(const SweepOptions& o);

}  // namespace top_sim
