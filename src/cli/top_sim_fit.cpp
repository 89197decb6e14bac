// top_sim_fit stationary|trajectory DATA.csv [options]: see kUsage below and docs/analysis.md.
// Fits friction-law (and initial-condition) parameters; exit 0 ok, 1 output not written, 2 bad data or argument,
// 3 the fit did not converge (the result is still written).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include "arguments.hpp"
#include "command_line.hpp"
#include "fit_data.hpp"
#include "plot.hpp"
#include "run.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/format.hpp"
#include "top_sim/scene.hpp"

namespace {

const char* kUsage =
    "usage: top_sim_fit stationary DATA.csv --law paper|linearized|table [--slips LIST] [--json FILE] [--plot FILE.png]\n"
    "       top_sim_fit trajectory DATA.csv --scene SCENE.yaml --free NAMES [--sigma M] [--json FILE]\n"
    "  stationary: columns alpha, phi [rad] and optionally sigma_alpha, sigma_phi (header row required);\n"
    "              phi > pi/2 is mirrored to pi - phi (negative spin). Fits mu(s) to s = tan(phi/2), tan(alpha).\n"
    "  --law L      paper (mu_c, s_c), linearized (mu0, k; s0 fixed at 0.3) or table (mu at fixed slips)\n"
    "  --slips LIST table: the nodes, comma-separated (default: 4 spread over the data's s range)\n"
    "  --plot FILE  PNG of the points and the fitted law (python3 with matplotlib)\n"
    "  trajectory: columns t, contact_x, contact_y (as written by top_sim_run --csv; other columns ignored)\n"
    "  --scene F    the scene simulated; the free parameters start from its values\n"
    "  --free NAMES comma-separated scene keys, e.g. friction.mu_c,friction.s_c,initial.tilt\n"
    "  --sigma M    standard error of the positions [m] (default: estimated from the residuals)\n"
    "  --json FILE  the result as JSON (- for standard output)\n";

using top_sim_cli::BadArgument;

struct Arguments {
  std::string kind, data, law = "paper", json, plot, scene;
  std::vector<std::string> free;
  std::vector<double> slips;
  double sigma = 0.0;
};

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

double number(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v)) throw BadArgument{flag + " = '" + text + "': not a number"};
  return v;
}

// Reads the command line (throws BadArgument); false when it asked for --help.
bool parse_arguments(int argc, char** argv, Arguments& a) {
  std::vector<std::string> positional;
  top_sim_cli::CommandLine line;
  line.value("--law", [&](const std::string& v) { a.law = v; })
      .value("--json", [&](const std::string& v) { a.json = v; })
      .value("--plot", [&](const std::string& v) { a.plot = v; })
      .value("--scene", [&](const std::string& v) { a.scene = v; })
      .value("--free", [&](const std::string& v) { a.free = split_list(v); })
      .value("--sigma", [&](const std::string& v) { a.sigma = number("--sigma", v); })
      .value("--slips", [&](const std::string& v) {
        for (const auto& s : split_list(v)) a.slips.push_back(number("--slips", s));
      })
      .positionals(positional);
  if (!line.parse(argc, argv)) return false;
  if (positional.size() != 2) throw BadArgument{"needs the fit kind (stationary or trajectory) and one data file"};
  a.kind = positional[0];
  a.data = positional[1];
  if (a.kind != "stationary" && a.kind != "trajectory")
    throw BadArgument{"fit kind '" + a.kind + "': must be stationary or trajectory"};
  if (a.kind == "trajectory" && (a.scene.empty() || a.free.empty()))
    throw BadArgument{"trajectory needs --scene SCENE.yaml and --free NAMES"};
  if (a.kind == "stationary" && a.law != "paper" && a.law != "linearized" && a.law != "table")
    throw BadArgument{"--law = '" + a.law + "': must be paper, linearized or table"};
  if (a.kind == "trajectory" && !a.plot.empty()) throw BadArgument{"--plot is for stationary fits"};
  return true;
}

std::ifstream open_data(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw top_sim::FitError(path + ": cannot open for reading");
  return in;
}

void print_result(const top_sim::FitResult& r, double cpu) {
  for (std::size_t i = 0; i < r.names.size(); ++i)
    std::cout << r.names[i] << " = " << top_sim::format_number(r.values[static_cast<Eigen::Index>(i)]) << " +- "
              << top_sim::format_number(r.errors[static_cast<Eigen::Index>(i)]) << "\n";
  std::cout << "chi2 " << r.chi2 << ", dof " << r.dof << (r.sigma_known ? "" : " (errors scaled by chi2/dof)")
            << ", " << r.evaluations << " evaluations, " << cpu << " s CPU, " << r.message << "\n";
}

// Points and fitted curve to temporary CSV files, then scripts/plots/fit_stationary.py draws them.
bool plot_stationary(const Arguments& a, const std::vector<top_sim::StationaryMeasurement>& data,
                     const top_sim::FitResult& r, const top_sim::StationaryFitOptions& opt) {
  using namespace top_sim;
  std::vector<SlipPoint> pts;
  for (const auto& d : data) pts.push_back(slip_point(d));
  const FrictionLaw law = fitted_law(r, opt, pts);
  const std::string points_csv = a.plot + ".points.csv", curve_csv = a.plot + ".curve.csv";
  {
    std::ofstream p(points_csv), c(curve_csv);
    p << "s,y,sigma_s,sigma_y,mirrored\n";
    for (const auto& q : pts) p << q.s << "," << q.y << "," << q.sigma_s << "," << q.sigma_y << "," << q.mirrored << "\n";
    c << "s,mu\n";
    for (int i = 0; i <= 200; ++i) c << i / 200.0 << "," << raw_friction_coefficient(law, i / 200.0) << "\n";
    if (!p || !c) return false;
  }
  std::ostringstream label;
  label << std::setprecision(3) << a.law << " fit:";
  for (std::size_t i = 0; i < r.names.size(); ++i)
    label << " " << r.names[i] << " " << r.values[static_cast<Eigen::Index>(i)] << " +- "
          << r.errors[static_cast<Eigen::Index>(i)];
  const bool drawn =
      top_sim_cli::run_plot("top_sim_fit", "fit_stationary.py", {points_csv, curve_csv, a.plot, label.str()}, a.plot);
  std::filesystem::remove(points_csv);
  std::filesystem::remove(curve_csv);
  return drawn;
}

bool write_json(const std::string& path, const std::string& json) {
  if (path.empty()) return true;
  if (path == "-") return static_cast<bool>(std::cout << json << std::flush);
  std::ofstream out(path);
  out << json << std::flush;
  if (!out) std::cerr << "top_sim_fit: --json = '" << path << "': cannot write\n";
  return static_cast<bool>(out);
}

// Runs the fit asked for; throws FitError / SceneError on bad input.
int run_fit(const Arguments& a) {
  using namespace top_sim;
  std::ifstream in = open_data(a.data);
  const double cpu0 = thread_cpu_seconds();
  FitResult r;
  double cpu = 0.0;
  bool plotted = true;
  if (a.kind == "stationary") {
    const auto data = read_stationary_data(in, a.data);
    StationaryFitOptions opt;
    parse_friction_law_kind(a.law, opt.law);
    opt.table_slips = a.slips;
    r = fit_stationary(data, opt);
    cpu = thread_cpu_seconds() - cpu0;  // the fit only, not the plot
    if (!a.plot.empty()) plotted = plot_stationary(a, data, r, opt);
  } else {
    const auto data = read_trajectory_data(in, a.data);
    const Scene scene = load_scene(a.scene);
    TrajectoryFitOptions opt;
    opt.sigma_position = a.sigma;
    r = fit_trajectory(scene, data, a.free, opt);
    cpu = thread_cpu_seconds() - cpu0;
  }
  if (a.json != "-") print_result(r, cpu);
  const bool written = write_json(a.json, fit_json(r, a.kind, cpu)) && plotted;
  if (r.sigma_known && r.dof > 0 && r.chi2 > r.dof + 5.0 * std::sqrt(2.0 * r.dof))  // 5 sigma above chi2's mean
    std::cerr << "top_sim_fit: warning: chi2 = " << r.chi2 << " for " << r.dof
              << " degrees of freedom: the model does not fit the data within the given sigma (a local minimum? "
                 "wrong sigma?)\n";
  for (const std::string& name : r.at_bound)
    std::cerr << "top_sim_fit: warning: " << name << " ended on the bound of its allowed range (the solver asked "
              << "for a value beyond it): the optimum is constrained there and its error is not meaningful\n";
  if (!r.converged) {
    std::cerr << "top_sim_fit: the fit did not converge: " << r.message << "\n";
    return 3;
  }
  return written ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (const auto done = top_sim_cli::parse_command_line("top_sim_fit", kUsage, parse_arguments, argc, argv, args))
    return *done;
  try {
    return run_fit(args);
  } catch (const top_sim::FitError& e) {
    std::cerr << "top_sim_fit: bad data: " << e.what() << "\n";
  } catch (const top_sim::SceneError& e) {
    std::cerr << "top_sim_fit: bad scene: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "top_sim_fit: " << e.what() << "\n";
  }
  return 2;
}
