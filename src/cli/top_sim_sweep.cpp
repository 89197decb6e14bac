// top_sim_sweep: a grid over alpha (and top, plane, spin, mu_c, s_c); each point simulated until it
// sleeps or slides; one CSV row per point with the measured and the analytic tan(phi*/2).
// Exit 0 ok, 2 bad argument, 3 when some point ended in a contact fault (its row says so).
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "arguments.hpp"
#include "sweep_options.hpp"

namespace {

using top_sim::SweepPoint;
using top_sim::SweepResult;
using top_sim::SweepSettings;

// Reads argv into `o` with the shared parser (sweep_options.cpp); false when it asked for --help.
bool parse_arguments(int argc, char** argv, top_sim::SweepOptions& o) {
  const bool go_on = top_sim::parse_sweep_options(std::vector<std::string>(argv + 1, argv + argc), o);
  if (o.threads == 0) o.threads = std::max(1u, std::thread::hardware_concurrency());
  return go_on;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Simulates every point on `threads` workers, with a progress line on a terminal.
std::vector<SweepResult> run_grid(const std::vector<SweepPoint>& grid, const SweepSettings& settings, unsigned threads,
                                  std::chrono::steady_clock::time_point wall0) {
  const bool tty = isatty(fileno(stderr));
  std::vector<SweepResult> results(grid.size());
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex progress_mutex;
  auto worker = [&]() {
    for (std::size_t i = next++; i < grid.size(); i = next++) {
      results[i] = top_sim::run_sweep_point(grid[i], settings);
      std::lock_guard<std::mutex> lock(progress_mutex);
      ++done;
      if (tty) {
        std::fprintf(stderr, "\r[%zu/%zu] %s/%s alpha %.4f spin %g: %-11s %7.1f s simulated, %5.1f s wall   ",
                     done, grid.size(), grid[i].top.c_str(), grid[i].plane.c_str(), grid[i].alpha, grid[i].spin,
                     results[i].outcome.c_str(), results[i].sim_seconds, seconds_since(wall0));
        std::fflush(stderr);
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned k = 0; k < threads; ++k) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (tty) std::fprintf(stderr, "\n");
  return results;
}

// The CSV and a summary line on stderr; the exit status (3 when some point ended in a contact fault).
int write_results(std::ostream& out, const std::vector<SweepResult>& results, unsigned threads,
                  std::chrono::steady_clock::time_point wall0) {
  top_sim::write_sweep_header(out);
  double cpu = 0.0;
  int faults = 0;
  for (const auto& r : results) {
    top_sim::write_sweep_row(out, r);
    cpu += r.cpu_seconds;
    if (r.outcome == "contact_fault") {
      ++faults;
      std::cerr << "top_sim_sweep: contact fault at alpha " << r.point.alpha << ": " << r.note << "\n";
    }
  }
  out.flush();
  std::cerr << "top_sim_sweep: " << results.size() << " points on " << threads << " threads in "
            << seconds_since(wall0) << " s wall, " << cpu << " s CPU\n";
  return faults > 0 ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  top_sim::SweepOptions opt;
  const std::string usage = std::string("usage: top_sim_sweep [options]\n") + top_sim::kSweepOptionsUsage;
  if (const auto done = top_sim_cli::parse_command_line("top_sim_sweep", usage.c_str(), parse_arguments, argc, argv, opt))
    return *done;

  // The grid, every scene validated before any simulation starts.
  const std::vector<SweepPoint> grid = top_sim::make_sweep_grid(opt);
  try {
    for (const auto& p : grid) top_sim::make_sweep_scene(p, opt.settings);
  } catch (const top_sim::SceneError& e) {
    std::cerr << "top_sim_sweep: bad grid point: " << e.what() << "\n";
    return 2;
  }

  std::ofstream file;
  if (opt.out_path != "-") {
    file.open(opt.out_path);
    if (!file) {
      std::cerr << "top_sim_sweep: --out = '" << opt.out_path << "': cannot open for writing\n";
      return 2;
    }
  }
  std::ostream& out = opt.out_path == "-" ? std::cout : file;

  const auto wall0 = std::chrono::steady_clock::now();
  const unsigned threads = std::min<unsigned>(opt.threads, static_cast<unsigned>(grid.size()));
  const std::vector<SweepResult> results = run_grid(grid, opt.settings, threads, wall0);
  return write_results(out, results, threads, wall0);
}
