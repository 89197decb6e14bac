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
#include "sweep_point.hpp"
#include "top_sim/friction.hpp"

namespace {

using top_sim::SweepPoint;
using top_sim::SweepResult;
using top_sim::SweepSettings;

const char* kUsage =
    "usage: top_sim_sweep [options]\n"
    "  Grid (LIST = comma-separated values, or A:B:N = N evenly spaced values from A to B inclusive):\n"
    "  --alpha LIST        inclinations [rad], each in (0, pi/2) (default 0.01:0.30:30)\n"
    "  --top LIST          top names in config/tops or .yaml paths (default aluminium)\n"
    "  --plane LIST        plane (friction) names in config/planes or .yaml paths (default pmma)\n"
    "  --spin LIST         initial shell spin [rad/s], nonzero (default 200)\n"
    "  --mu-c LIST         override the paper law's mu_c, > 0\n"
    "  --s-c LIST          override the paper law's s_c, in (0, 1]\n"
    "  Each point:\n"
    "  --start MODE        tilted (default: at rest, figure axis tilted by --tilt) | launched (the analytic\n"
    "                      sleeping state perturbed by --perturbation of extra tilt: slip starts near s*,\n"
    "                      not at the s = 1 of a top at rest, which runs away close to alpha_c)\n"
    "  --tilt RAD          initial tilt from the vertical (tilted start), in [0, 1) (default 0.1)\n"
    "  --perturbation RAD  extra tilt of the launched start, in [0, 0.5] (default 0.01)\n"
    "  --max-path M        give up after this sleeping-path length [m], > 0 (default 40)\n"
    "  --max-duration S    and never after more than S simulated seconds, > 0 (default 20000)\n"
    "  --slide-duration S  sliding must persist this long to count; run length above alpha_c (default 30)\n"
    "  --tol RAD           converged when successive windows' travel angles differ by less, > 0 (default 1e-6)\n"
    "  Output:\n"
    "  --out FILE          CSV file (default - = standard output)\n"
    "  --threads N         worker threads, 1..1024 (default: all cores)\n"
    "  --config DIR        directory holding tops/ and planes/ (default: the installed config)\n";

using top_sim_cli::BadArgument;

double parse_number(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw BadArgument{flag + " = '" + text + "': not a finite number"};
  return v;
}

template <class Ok>
double checked(const std::string& flag, const std::string& text, Ok ok, const std::string& range) {
  const double v = parse_number(flag, text);
  if (!ok(v)) throw BadArgument{flag + " = '" + text + "': must be " + range};
  return v;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string item;
  std::istringstream is(text);
  while (std::getline(is, item, sep)) parts.push_back(item);
  if (!text.empty() && text.back() == sep) parts.push_back("");
  return parts;
}

// LIST of numbers: "a,b,c" or "A:B:N"; every value checked against the flag's range.
template <class Ok>
std::vector<double> number_list(const std::string& flag, const std::string& text, Ok ok, const std::string& range) {
  std::vector<double> values;
  const auto colon = split(text, ':');
  if (colon.size() == 3) {
    const double a = checked(flag, colon[0], ok, range), b = checked(flag, colon[1], ok, range);
    const double n = parse_number(flag, colon[2]);
    if (n < 1 || n > 100000 || n != std::floor(n))
      throw BadArgument{flag + " = '" + text + "': the count N of A:B:N must be an integer in [1, 100000]"};
    if (b < a) throw BadArgument{flag + " = '" + text + "': A:B:N needs A <= B"};
    const int count = static_cast<int>(n);
    for (int i = 0; i < count; ++i) values.push_back(count == 1 ? a : a + (b - a) * i / (count - 1));
  } else if (colon.size() == 1) {
    for (const auto& item : split(text, ',')) values.push_back(checked(flag, item, ok, range));
  } else {
    throw BadArgument{flag + " = '" + text + "': expected a comma-separated list or A:B:N"};
  }
  if (values.empty()) throw BadArgument{flag + " = '" + text + "': empty list"};
  return values;
}

std::vector<std::string> name_list(const std::string& flag, const std::string& text) {
  auto names = split(text, ',');
  for (const auto& n : names)
    if (n.empty()) throw BadArgument{flag + " = '" + text + "': empty name in the list"};
  if (names.empty()) throw BadArgument{flag + " = '" + text + "': empty list"};
  return names;
}

// The command line: the grid, how each point runs, the output.
struct Options {
  std::vector<double> alphas, spins = {200.0};
  std::vector<std::string> tops = {"aluminium"}, planes = {"pmma"};
  std::vector<std::optional<double>> mu_cs = {std::nullopt}, s_cs = {std::nullopt};
  SweepSettings settings;
  std::string out_path = "-";
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
};

using Value = std::function<std::string()>;  // the flag's value (throws BadArgument when it has none)

// One of the grid's flags into `o`; false when `flag` is not a grid flag.
bool read_grid_option(const std::string& a, const Value& value, Options& o) {
  if (a == "--alpha") {
    o.alphas = number_list(a, value(), [](double v) { return v > 0.0 && v < M_PI / 2; }, "in (0, pi/2) [rad]");
  } else if (a == "--spin") {
    o.spins = number_list(a, value(), [](double v) { return v != 0.0 && std::abs(v) <= 1e5; },
                          "nonzero with |spin| <= 1e5 [rad/s]");
  } else if (a == "--mu-c" || a == "--s-c") {
    const bool mu = a == "--mu-c";
    const top_sim::ParameterRange range = top_sim::find_friction_parameter(mu ? "mu_c" : "s_c")->range;
    const auto v = number_list(a, value(), [range](double x) { return range.admits(x); }, range.text());
    auto& target = mu ? o.mu_cs : o.s_cs;
    target.assign(v.begin(), v.end());
  } else if (a == "--top") {
    o.tops = name_list(a, value());
  } else if (a == "--plane") {
    o.planes = name_list(a, value());
  } else {
    return false;
  }
  return true;
}

// One of the flags of each point's run or of the output into `o`; false when `flag` is none of them.
bool read_run_option(const std::string& a, const Value& value, Options& o) {
  SweepSettings& settings = o.settings;
  if (a == "--start") {
    const std::string s = value();
    if (s == "tilted") settings.start = top_sim::SweepStart::tilted;
    else if (s == "launched") settings.start = top_sim::SweepStart::launched;
    else throw BadArgument{a + " = '" + s + "': must be tilted | launched"};
  } else if (a == "--tilt") {
    settings.tilt = checked(a, value(), [](double v) { return v >= 0.0 && v < 1.0; }, "in [0, 1) [rad]");
  } else if (a == "--perturbation") {
    settings.launch_perturbation = checked(a, value(), [](double v) { return v >= 0.0 && v <= 0.5; }, "in [0, 0.5] [rad]");
  } else if (a == "--max-path") {
    settings.max_path = checked(a, value(), [](double v) { return v > 0.0; }, "> 0 [m]");
  } else if (a == "--max-duration") {
    settings.max_duration = checked(a, value(), [](double v) { return v > 0.0; }, "> 0 [s]");
    settings.min_duration = std::min(settings.min_duration, settings.max_duration);
  } else if (a == "--slide-duration") {
    settings.slide_duration = checked(a, value(), [](double v) { return v > 0.0; }, "> 0 [s]");
  } else if (a == "--tol") {
    settings.phi_tolerance = checked(a, value(), [](double v) { return v > 0.0; }, "> 0 [rad]");
  } else if (a == "--threads") {
    o.threads = static_cast<unsigned>(checked(a, value(), [](double v) { return v >= 1 && v <= 1024 && v == std::floor(v); },
                                              "an integer in [1, 1024]"));
  } else if (a == "--out") {
    o.out_path = value();
  } else if (a == "--config") {
    settings.config_dir = value();
  } else {
    return false;
  }
  return true;
}

// Reads the command line into `o` (throws BadArgument); false when it asked for --help.
bool parse_arguments(int argc, char** argv, Options& o) {
  o.alphas = number_list("--alpha", "0.01:0.30:30", [](double) { return true; }, "");
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const Value value = [&]() -> std::string {
      if (i + 1 >= argc) throw BadArgument{a + ": needs a value"};
      return argv[++i];
    };
    if (a == "-h" || a == "--help") return false;
    if (!read_grid_option(a, value, o) && !read_run_option(a, value, o))
      throw BadArgument{"unknown argument '" + a + "'"};
  }
  return true;
}

std::vector<SweepPoint> make_grid(const Options& o) {
  std::vector<SweepPoint> grid;
  for (const auto& top : o.tops)
    for (const auto& plane : o.planes)
      for (const auto& mu_c : o.mu_cs)
        for (const auto& s_c : o.s_cs)
          for (double spin : o.spins)
            for (double alpha : o.alphas) grid.push_back(SweepPoint{top, plane, alpha, spin, mu_c, s_c});
  return grid;
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
  Options opt;
  if (const auto done = top_sim_cli::parse_command_line("top_sim_sweep", kUsage, parse_arguments, argc, argv, opt))
    return *done;

  // The grid, every scene validated before any simulation starts.
  const std::vector<SweepPoint> grid = make_grid(opt);
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
