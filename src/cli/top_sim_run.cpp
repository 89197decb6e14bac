// top_sim_run SCENE.yaml [options]: see kUsage below and docs/interfaces.md.
// Runs one scene without ROS; exit 0 ok, 1 output not written, 2 bad scene or argument, 3 contact or numerical fault.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>
#include <unistd.h>

#include "arguments.hpp"
#include "command_line.hpp"
#include "writers.hpp"
#include "top_sim/format.hpp"
#include "top_sim/pacing.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#ifdef TOP_SIM_HAVE_LCM
#include "lcm_publisher.hpp"
#endif

namespace {

const char* kUsage =
    "usage: top_sim_run SCENE [--duration S] [--csv FILE] [--rate HZ] [--summary FILE|-]\n"
    "                   [--lcm URL [--lcm-channel NAME]] [--quiet] [--progress]\n"
    "  SCENE           a scene file (a path: contains '/' or ends in .yaml) or a shipped scene's name, e.g. tippe_top\n"
    "  --duration S    simulated seconds (default: the scene's duration)\n"
    "  --csv FILE      write the state at --rate samples per simulated second\n"
    "  --rate HZ       sample rate of the CSV and of --lcm (default 100)\n"
    "  --summary FILE  write the JSON summary (- for standard output)\n"
    "  --lcm URL       stream top_sim.top_state_t in real time at --rate Hz over LCM (e.g. udpm://239.255.76.67:7667?ttl=0)\n"
    "  --lcm-channel C LCM channel (default TOP_STATE)\n"
    "  --quiet         no progress line (shown on a terminal during runs longer than 1 s of wall time)\n"
    "  --progress      progress lines even when standard error is not a terminal\n"
    "CSV files are limited to 1e8 rows (--duration x --rate; ~20 GB).\n";

constexpr double kMaxCsvRows = 1.0e8;

using top_sim_cli::BadArgument;

double positive_number(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v <= 0.0)
    throw BadArgument{flag + " = '" + text + "': must be a number > 0"};
  return v;
}

struct Arguments {
  std::string scene_path, csv_path, summary_path, lcm_url, lcm_channel = "TOP_STATE";
  double duration = -1.0;  // < 0: the scene's
  double rate = 100.0;     // samples per simulated second
  bool quiet = false, progress = false;
};

// Reads the command line (throws BadArgument); false when it asked for --help.
bool parse_arguments(int argc, char** argv, Arguments& args) {
  std::vector<std::string> scenes;
  top_sim_cli::CommandLine line;
  line.value("--duration", [&](const std::string& v) { args.duration = positive_number("--duration", v); })
      .value("--rate", [&](const std::string& v) { args.rate = positive_number("--rate", v); })
      .flag("--quiet", [&] { args.quiet = true; })
      .flag("--progress", [&] { args.progress = true; })
      .value("--csv", [&](const std::string& v) { args.csv_path = v; })
      .value("--summary", [&](const std::string& v) { args.summary_path = v; })
      .value("--lcm", [&](const std::string& v) {
        if (v.empty()) throw BadArgument{"--lcm = '': must be an LCM URL such as udpm://239.255.76.67:7667?ttl=0"};
        args.lcm_url = v;
      })
      .value("--lcm-channel", [&](const std::string& v) {
        if (v.empty()) throw BadArgument{"--lcm-channel = '': must be a non-empty channel name"};
        args.lcm_channel = v;
      })
      .positionals(scenes);
  if (!line.parse(argc, argv)) return false;
  args.scene_path = top_sim_cli::one_positional(scenes, "scene file");
#ifndef TOP_SIM_HAVE_LCM
  if (!args.lcm_url.empty()) throw BadArgument{"--lcm: this build has no LCM support (liblcm-dev and lcm-gen were not found)"};
#endif
  return true;
}

#ifdef TOP_SIM_HAVE_LCM
// Real time (factor 1), paced by top_sim::Pacer like top_sim_node: each sample waits for its wall-clock instant, then
// goes out on LCM with the achieved factor of the last wall second (and to the CSV when one is written). A sample
// more than 0.5 s late re-anchors the clock (the debt is dropped) instead of rushing the backlog out.
void stream_over_lcm(top_sim_lcm::Publisher& lcm, const std::string& channel, double rate, const top_sim::Simulator& sim,
                     top_sim::RunOptions& opt) {
  const double t0 = sim.time();
  using clock = std::chrono::steady_clock;
  const clock::time_point wall0 = clock::now();
  auto wall_now = [wall0] { return std::chrono::duration<double>(clock::now() - wall0).count(); };
  auto pacer = std::make_shared<top_sim::Pacer>(1.0, rate, 0.0, t0);
  auto write_csv = opt.on_sample;
  opt.sample_rate = rate;
  opt.on_sample = [&lcm, &sim, channel, write_csv, wall0, wall_now, pacer](const top_sim::Snapshot& s) {
    const double at = pacer->due(wall_now(), s.t);
    std::this_thread::sleep_until(wall0 + std::chrono::duration_cast<clock::duration>(
                                              std::chrono::duration<double>(at)));
    const bool was_behind = pacer->behind();
    pacer->record(wall_now(), s.t);
    if (pacer->behind() != was_behind) {
      if (pacer->behind())
        std::cerr << "top_sim_run: falling behind: achieved " << pacer->achieved_factor()
                  << " of requested 1 at t = " << s.t << " s\n";
      else
        std::cerr << "top_sim_run: caught up at t = " << s.t << " s\n";
    }
    static bool warned = false;  // one message, not one per sample
    const char* law = top_sim::to_string(sim.model().friction.kind);  // in force: scene events may change it
    if (!lcm.publish(s, {pacer->achieved_factor(), 1.0, false, law}) && !warned && (warned = true))
      std::cerr << "top_sim_run: LCM publish on " << channel << " failed at t = " << s.t << " s\n";
    if (write_csv) write_csv(s);
  };
}
#endif

// The scene (a file or a shipped scene's name), its warnings on stderr; false (after the message) when it is bad.
bool load(const std::string& path, top_sim::Scene& scene) {
  try {
    scene = top_sim::load_scene(top_sim::scene_path(path));
  } catch (const top_sim::SceneError& e) {
    std::cerr << "top_sim_run: bad scene: " << e.what() << "\n";
    return false;
  } catch (const std::exception& e) {  // never an abort on input: whatever escaped the loader is still bad input
    std::cerr << "top_sim_run: bad scene: " << path << ": " << e.what() << "\n";
    return false;
  }
  for (const auto& w : scene.warnings) std::cerr << "top_sim_run: warning: " << w << "\n";
  return true;
}

// The CSV with its header when a path is given; false (after the message) when it cannot be written or would
// exceed kMaxCsvRows.
bool open_csv(const std::string& path, double duration, double rate, std::ofstream& csv) {
  if (path.empty()) return true;
  if (duration * rate + 1.0 > kMaxCsvRows) {
    std::cerr << "top_sim_run: --rate " << top_sim::format_number(rate) << " over --duration "
              << top_sim::format_number(duration) << " s asks for " << top_sim::format_number(duration * rate + 1.0)
              << " CSV rows; must be <= 1e8 rows (lower --rate or --duration)\n";
    return false;
  }
  csv.open(path);
  if (!csv) {
    std::cerr << "top_sim_run: --csv = '" << path << "': cannot open for writing\n";
    return false;
  }
  return true;
}

// "t = 12 s of 300 s (4 %)" on stderr: one line per report (a terminal sees them overwrite each other).
std::function<void(double)> progress_printer(double t0, double duration) {
  const bool tty = isatty(STDERR_FILENO);
  return [t0, duration, tty](double t) {
    std::cerr << (tty ? "\r" : "") << "top_sim_run: t = " << t - t0 << " s of " << duration << " s ("
              << static_cast<int>(100.0 * (t - t0) / duration) << " %)" << (tty ? "   " : "\n") << std::flush;
  };
}

// The one-line result on stdout (unless the summary goes there).
void print_result(const top_sim::Scene& scene, const top_sim::RunResult& r) {
  std::cout << scene.source << ": " << r.sim_seconds << " s simulated in " << r.cpu_seconds << " s CPU ("
            << r.stats.steps << " steps, " << r.stats.rhs_evaluations << " right-hand sides), regime "
            << top_sim::to_string(r.final.regime);
  if (r.phi_measured) std::cout << ", phi_measured " << *r.phi_measured;
  if (r.phi_star) std::cout << ", phi_star " << *r.phi_star;
  if (r.phi_measured && r.phi_star) std::cout << " (difference " << std::abs(*r.phi_measured - *r.phi_star) << ")";
  std::cout << ", energy residual " << r.max_energy_residual << "\n";
  if (!r.stationary_note.empty()) std::cout << "  stationary state: " << r.stationary_note << "\n";
}

// True when every CSV row reached the file; else says so.
bool csv_written(const std::string& path, std::ofstream& csv) {
  if (!csv.is_open()) return true;
  csv.flush();
  if (!csv) std::cerr << "top_sim_run: --csv = '" << path << "': writing failed (disk full?); the file is incomplete\n";
  return static_cast<bool>(csv);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace top_sim;
  Arguments args;
  if (const auto done = top_sim_cli::parse_command_line("top_sim_run", kUsage, parse_arguments, argc, argv, args))
    return *done;

  Scene scene;
  std::ofstream csv;
  if (!load(args.scene_path, scene)) return 2;
  const double duration = args.duration > 0.0 ? args.duration : scene.duration;
  if (!open_csv(args.csv_path, duration, args.rate, csv)) return 2;

  Simulator sim(scene);
  RunOptions opt;
  opt.duration = duration;
  if (args.progress || (!args.quiet && isatty(STDERR_FILENO))) opt.on_progress = progress_printer(sim.time(), duration);
  CsvWriter rows(csv);
  if (csv.is_open()) {  // only the CSV (and --lcm) reads samples: the summary's regime_seconds are the simulator's
    opt.sample_rate = args.rate;
    rows.header();
    opt.on_sample = [&rows](const Snapshot& s) { rows.row(s); };
  }
#ifdef TOP_SIM_HAVE_LCM
  std::unique_ptr<top_sim_lcm::Publisher> lcm;
  if (!args.lcm_url.empty()) {
    lcm = std::make_unique<top_sim_lcm::Publisher>(args.lcm_url, args.lcm_channel);
    if (!lcm->ok()) {
      std::cerr << "top_sim_run: --lcm = '" << args.lcm_url << "': " << lcm->error() << "\n";
      return 2;
    }
    stream_over_lcm(*lcm, args.lcm_channel, args.rate, sim, opt);
  }
#endif
  const RunResult r = run(sim, opt);
  if (opt.on_progress && isatty(STDERR_FILENO)) std::cerr << "\n";
  // Output errors surface after the simulation: exit 1 (the result could not be delivered).
  rows.flush();
  const bool written = csv_written(args.csv_path, csv) &&
                       write_text_file("top_sim_run", "--summary", args.summary_path, summary_json(scene, r));
  if (args.summary_path != "-") print_result(scene, r);
  if (r.final.fault != ContactFault::none) {
    std::cerr << "top_sim_run: contact fault: " << r.final.fault_message << "\n";
    return 3;
  }
  return written ? 0 : 1;
}
