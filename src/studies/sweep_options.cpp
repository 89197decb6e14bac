#include "sweep_options.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "arguments.hpp"
#include "command_line.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/limits.hpp"

namespace top_sim {

const char* const kSweepOptionsUsage =
    "  Grid (LIST = comma-separated values, or A:B:N = N evenly spaced values from A to B inclusive):\n"
    "  --alpha LIST        inclinations [rad], each in (0, pi/2) (default 0.01:0.30:30)\n"
    "  --top LIST          top names in config/tops or .yaml paths (default aluminium)\n"
    "  --plane LIST        plane (friction) names in config/planes or .yaml paths (default pmma)\n"
    "  --spin LIST         initial shell spin [rad/s], nonzero (default 200)\n"
    "  --mu-c LIST         override the paper law's mu_c, > 0\n"
    "  --s-c LIST          override the paper law's s_c, in (0, 1]\n"
    "  --patch-radius LIST contact.patch_radius (physics.md section 12): each >= 0 [m], or hertz (from the normal\n"
    "                      force and the top's and plane's materials) (default 0 = the point contact)\n"
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
    "  --threads N         parallel workers, 1..1024 (default: all cores)\n"
    "  --config DIR        directory holding tops/ and planes/ (default: the installed config)\n";

namespace {

using top_sim_cli::BadArgument;

using top_sim_cli::finite_number;

template <class Ok>
double checked(const std::string& flag, const std::string& text, Ok ok, const std::string& range) {
  const double v = finite_number(flag, text);
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
    const double n = finite_number(flag, colon[2]);
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

// --patch-radius's LIST: A:B:N of numbers, or comma-separated items each a number or hertz.
std::vector<PatchRadius> patch_list(const std::string& flag, const std::string& text) {
  const std::string range = ">= 0 [m], or hertz";
  const auto admits = [](double v) { return v >= 0.0; };
  std::vector<PatchRadius> patches;
  if (text.find(':') != std::string::npos) {
    try {
      for (double v : number_list(flag, text, admits, range)) patches.push_back(PatchRadius{v, false});
    } catch (const BadArgument& e) {
      if (e.message.find(range) != std::string::npos) throw;
      throw BadArgument{e.message + " (each radius " + range + ")"};  // "not a finite number" names no range
    }
    return patches;
  }
  const auto items = split(text, ',');
  if (items.empty()) throw BadArgument{flag + " = '" + text + "': empty list"};
  for (const auto& item : items) {
    if (item == "hertz") {
      patches.push_back(PatchRadius{0.0, true});
      continue;
    }
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v) || !admits(v))
      throw BadArgument{flag + " = '" + text + "': " + (items.size() > 1 ? "the item '" + item + "' " : "") +
                        "must be " + range};
    patches.push_back(PatchRadius{v, false});
  }
  return patches;
}

using top_sim_cli::CommandLine;
using Text = const std::string&;

// The grid's flags, read into `o`.
void add_grid_options(CommandLine& line, SweepOptions& o) {
  line.value("--alpha", [&o](Text v) {
    o.alphas = number_list("--alpha", v, [](double a) { return a > 0.0 && admissible_inclination(a); },
                           "in (0, pi/2) [rad]");
  });
  line.value("--spin", [&o](Text v) {
    o.spins = number_list("--spin", v, [](double w) { return w != 0.0 && std::abs(w) <= 1e5; },
                          "nonzero with |spin| <= 1e5 [rad/s]");
  });
  for (const bool mu : {true, false}) {
    const std::string flag = mu ? "--mu-c" : "--s-c";
    line.value(flag, [&o, mu, flag](Text v) {
      const ParameterRange range = find_friction_parameter(mu ? "mu_c" : "s_c")->range;
      const auto values = number_list(flag, v, [range](double x) { return range.admits(x); }, range.text());
      (mu ? o.mu_cs : o.s_cs).assign(values.begin(), values.end());
    });
  }
  line.value("--patch-radius", [&o](Text v) { o.patches = patch_list("--patch-radius", v); });
  line.value("--top", [&o](Text v) { o.tops = name_list("--top", v); });
  line.value("--plane", [&o](Text v) { o.planes = name_list("--plane", v); });
}

// `flag`'s value into `target`: a number admitted by `ok`, described by `range`.
template <class Ok>
void add_checked(CommandLine& line, const std::string& flag, double& target, Ok ok, const std::string& range) {
  line.value(flag, [&target, flag, ok, range](Text v) { target = checked(flag, v, ok, range); });
}

// The flags of each point's run and of the output, read into `o`.
void add_run_options(CommandLine& line, SweepOptions& o) {
  SweepSettings& settings = o.settings;
  line.value("--start", [&settings](Text v) {
    if (v == "tilted") settings.start = SweepStart::tilted;
    else if (v == "launched") settings.start = SweepStart::launched;
    else throw BadArgument{"--start = '" + v + "': must be tilted | launched"};
  });
  add_checked(line, "--tilt", settings.tilt, [](double v) { return v >= 0.0 && v < 1.0; }, "in [0, 1) [rad]");
  add_checked(line, "--perturbation", settings.launch_perturbation, [](double v) { return v >= 0.0 && v <= 0.5; },
              "in [0, 0.5] [rad]");
  add_checked(line, "--max-path", settings.max_path, [](double v) { return v > 0.0; }, "> 0 [m]");
  line.value("--max-duration", [&settings](Text v) {
    settings.max_duration = checked("--max-duration", v, [](double d) { return d > 0.0; }, "> 0 [s]");
    settings.min_duration = std::min(settings.min_duration, settings.max_duration);
  });
  add_checked(line, "--slide-duration", settings.slide_duration, [](double v) { return v > 0.0; }, "> 0 [s]");
  add_checked(line, "--tol", settings.phi_tolerance, [](double v) { return v > 0.0; }, "> 0 [rad]");
  line.value("--threads", [&o](Text v) {
    const auto whole = [](double n) { return n >= 1 && n <= 1024 && n == std::floor(n); };
    o.threads = static_cast<unsigned>(checked("--threads", v, whole, "an integer in [1, 1024]"));
  });
  line.value("--out", [&o](Text v) { o.out_path = v; });
  line.value("--config", [&settings](Text v) { settings.config_dir = v; });
}

}  // namespace

bool parse_sweep_options(const std::vector<std::string>& args, SweepOptions& o) {
  o.alphas = number_list("--alpha", "0.01:0.30:30", [](double) { return true; }, "");
  CommandLine line("unknown argument");  // a sweep takes no positional argument
  add_grid_options(line, o);
  add_run_options(line, o);
  return line.parse(args);
}

std::vector<SweepPoint> make_sweep_grid(const SweepOptions& o) {
  std::vector<SweepPoint> grid;
  for (const auto& top : o.tops)
    for (const auto& plane : o.planes)
      for (const auto& mu_c : o.mu_cs)
        for (const auto& s_c : o.s_cs)
          for (const auto& patch : o.patches)
            for (double spin : o.spins)
              for (double alpha : o.alphas) grid.push_back(SweepPoint{top, plane, alpha, spin, mu_c, s_c, patch});
  return grid;
}

}  // namespace top_sim
