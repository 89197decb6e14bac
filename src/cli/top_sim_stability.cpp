// top_sim_stability SCENE.yaml [options]: the linear stability of the scene's sleeping state (physics.md section
// 10, include/top_sim/stability.hpp), or of a tippe top's spinning upright or inverted state (--state); see kUsage
// below, docs/interfaces.md and docs/analysis.md.
// Exit 0 ok, 1 an output (JSON, plot) not written, 2 bad scene or argument, 3 no state to analyse.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arguments.hpp"
#include "command_line.hpp"
#include "plot.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/format.hpp"
#include "top_sim/limits.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/stability.hpp"

extern char** environ;

namespace {

using top_sim::Eigenvalue;
using top_sim::format_number;
using top_sim::SpinningState;
using top_sim::StabilityResult;

const char* kUsage =
    "usage: top_sim_stability SCENE.yaml [--state upright|inverted] [--spin W] [--json FILE|-]\n"
    "                         [--sweep-alpha A0:A1:N] [--sweep-spin W0:W1:N] [--plot FILE.png]\n"
    "  Linear stability of the scene's sleeping state (physics.md section 10): eigenvalues of the Jacobian of the\n"
    "  right-hand side over u, f_hat (tangent plane), omega (and nu with a rotor), classified.\n"
    "  --state S              a tippe top (top.com_offset < 0) on a level plane: its spinning state S, upright\n"
    "                         (f_hat = +n, the centre of mass below the sphere's centre) or inverted (f_hat = -n,\n"
    "                         on the stem side), next to Magnus' critical spin; without --state a tippe top's\n"
    "                         --sweep-spin sweeps both states. An ordinary top (com_offset > 0): upright only,\n"
    "                         with a patch (contact.patch_radius), mu(0) > 0 or a frictionless plane; with\n"
    "                         --sweep-spin its critical spin (stable above) next to the Maxwell-Klein limit\n"
    "  --spin W               shell spin omega* [rad/s], nonzero, |W| <= 1e6 (default: the scene's initial.spin);\n"
    "                         a rotor keeps the scene's absolute rotor spin\n"
    "  --json FILE            the analysis at --spin as JSON (- = standard output)\n"
    "  --sweep-alpha A0:A1:N  spectrum at N inclinations from A0 to A1 (0 < A0 <= A1 < pi/2, N in [1, 10000]), and\n"
    "                         alpha_c located where stability is lost (bisection along the slip branch from A0)\n"
    "  --sweep-spin W0:W1:N   spectrum at N shell spins from W0 to W1 (|W| <= 1e6, N in [1, 10000]) at the scene's\n"
    "                         alpha, and the spin windows where nutation Re > 0 or any Re > 0 (a tippe top: any\n"
    "                         Re > 0, next to Magnus' critical spin)\n"
    "  --plot FILE.png        draw the sweep(s) (python3 with matplotlib: scripts/plots/stability.py)\n"
    "Exit status: 0 ok; 1 JSON or plot not written; 2 bad scene or argument; 3 no sleeping state to analyse at the\n"
    "scene's alpha and --spin (above alpha_c, or a top that does not move; the message says which), or no\n"
    "spinning state (an inclined plane, mu(0) = 0, max_tilt < pi for the inverted one).\n";

// Where the human-readable report goes: standard output, or standard error when the JSON goes there.
std::ostream* report = &std::cout;

using top_sim_cli::BadArgument;

double number(const std::string& flag, const std::string& text) {
  return top_sim_cli::finite_number(flag, text);
}

struct Range {
  double from = 0.0, to = 0.0;
  int count = 0;
};

// A0:A1:N with both ends admitted by `ok` (described by `range`) and N an integer in [1, 10000].
template <class Ok>
Range parse_range(const std::string& flag, const std::string& text, Ok ok, const std::string& range) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ':');) parts.push_back(item);
  if (parts.size() != 3 || text.back() == ':')
    throw BadArgument{flag + " = '" + text + "': expected FROM:TO:N"};
  Range r{number(flag, parts[0]), number(flag, parts[1]), 0};
  const double n = number(flag, parts[2]);
  if (!ok(r.from) || !ok(r.to)) throw BadArgument{flag + " = '" + text + "': FROM and TO must be " + range};
  if (r.to < r.from) throw BadArgument{flag + " = '" + text + "': needs FROM <= TO"};
  if (n < 1 || n > 10000 || n != std::floor(n))
    throw BadArgument{flag + " = '" + text + "': N must be an integer in [1, 10000]"};
  r.count = static_cast<int>(n);
  return r;
}

struct Arguments {
  std::string scene_path, json_path, plot_path;
  std::optional<double> spin;
  std::optional<Range> sweep_alpha, sweep_spin;
  std::optional<SpinningState> state;
};

bool admissible_alpha(double a) { return a > 0.0 && top_sim::admissible_inclination(a); }
bool admissible_spin(double w) { return std::abs(w) <= top_sim::kMaxSpin; }

// Reads the command line (throws BadArgument); false when it asked for --help.
bool parse_arguments(int argc, char** argv, Arguments& args) {
  const std::string spin_range = "in [-1e6, 1e6] [rad/s]";
  std::vector<std::string> scenes;
  top_sim_cli::CommandLine line;
  line.value("--state", [&](const std::string& text) {
    SpinningState st;
    if (!top_sim::parse_spinning_state(text, st))
      throw BadArgument{"--state = '" + text + "': must be upright or inverted"};
    args.state = st;
  });
  line.value("--spin", [&](const std::string& text) {
    const double w = number("--spin", text);
    if (w == 0.0 || !admissible_spin(w))
      throw BadArgument{"--spin = '" + text + "': must be nonzero and " + spin_range};
    args.spin = w;
  });
  line.value("--json", [&](const std::string& v) { args.json_path = v; })
      .value("--plot", [&](const std::string& v) { args.plot_path = v; })
      .value("--sweep-alpha", [&](const std::string& v) {
        args.sweep_alpha = parse_range("--sweep-alpha", v, admissible_alpha, "in (0, pi/2) [rad]");
      })
      .value("--sweep-spin", [&](const std::string& v) {
        args.sweep_spin = parse_range("--sweep-spin", v, admissible_spin, spin_range);
      })
      .positionals(scenes);
  if (!line.parse(argc, argv)) return false;
  args.scene_path = top_sim_cli::one_positional(scenes, "scene file");
  if (!args.plot_path.empty() && !args.sweep_alpha && !args.sweep_spin)
    throw BadArgument{"--plot = '" + args.plot_path + "': needs --sweep-alpha or --sweep-spin (it draws the sweeps)"};
  return true;
}

std::string complex_text(Eigenvalue v) {
  std::ostringstream os;
  os << std::setprecision(7) << v.real();
  if (v.imag() != 0.0) os << (v.imag() > 0 ? " + " : " - ") << std::abs(v.imag()) << "i";
  return os.str();
}

bool is_tippe_top(const top_sim::Scene& scene) { return scene.model.top.com_offset < 0.0; }

// Magnus' critical spin of a spinning state and what it means (docs/analysis.md).
std::string magnus_text(const top_sim::Model& model, SpinningState state) {
  const double wk2 = top_sim::magnus_critical_spin_squared(model, state);
  // The centre of mass below the sphere's centre (Magnus' a > 0): a tippe top upright, or an ordinary top inverted.
  const bool below = (state == SpinningState::upright) == (model.top.com_offset < 0.0);
  std::ostringstream os;
  os << std::setprecision(10) << "Magnus' critical spin (friction linear in the slip, docs/analysis.md): ";
  if (std::isfinite(wk2) && wk2 > 0.0)
    os << "omega_k = " << std::sqrt(wk2) << " rad/s: " << (below ? "stable below, unstable above" : "unstable below, stable above");
  else
    os << "omega_k^2 = " << wk2 << " <= 0: no crossing, " << (below ? "stable" : "unstable") << " at every spin";
  return os.str();
}

// An ordinary top's frictionless-plane limit (docs/analysis.md "The wake-up").
std::string maxwell_klein_text(const top_sim::Model& model) {
  std::ostringstream os;
  os << std::setprecision(10) << "Maxwell-Klein critical spin (frictionless plane, I_f^2 w^2 = 4 I_d m g f): "
     << top_sim::maxwell_klein_critical_spin(model) << " rad/s";
  return os.str();
}

// An ordinary top's upright state: the located critical spin (stable above), printed; NaN when none is found.
double report_critical_spin(const top_sim::Scene& scene, const Range& range) {
  const double hi = std::max(range.from, range.to);
  double lo = std::min(range.from, range.to);
  if (lo <= 0.0) lo = hi / std::max(range.count - 1, 1);  // spin 0 has no spinning state: the first positive point
  const top_sim::CriticalSpin c = top_sim::locate_critical_spin(scene.model, SpinningState::upright,
                                                                scene.initial.rotor_spin, lo, hi, range.count);
  (*report) << std::setprecision(10) << maxwell_klein_text(scene.model) << "\ncritical spin (largest Re but the zero "
            << "one crosses 1e-7 1/s, bisected): ";
  if (c.found)
    (*report) << c.spin << " rad/s (stable above; " << c.mode << " " << complex_text(c.eigenvalue)
              << " 1/s at the first unstable scan point)\n";
  else
    (*report) << "none: " << c.reason << "\n";
  return c.found ? c.spin : NAN;
}

// The single analysis, human-readable.
void print_analysis(const top_sim::Model& model, const StabilityResult& r, std::optional<SpinningState> state) {
  (*report) << std::setprecision(7);
  if (state)
    (*report) << "spinning " << top_sim::to_string(*state) << " state (f_hat = " << (*state == SpinningState::upright ? "+" : "-")
              << "n, u = 0, v_t = 0, level plane): shell spin " << r.spin << " rad/s";
  else
    (*report) << "sleeping state: alpha " << r.alpha << " rad, shell spin " << r.spin << " rad/s";
  if (model.top.has_rotor) (*report) << ", rotor spin " << r.rotor_spin << " rad/s";
  (*report) << (state ? "\n" + magnus_text(model, *state) : ", s* " + format_number(r.slip)) << "\n";
  if (state && model.top.com_offset > 0.0) (*report) << maxwell_klein_text(model) << "\n";
  (*report) << "eigenvalues [1/s] of the Jacobian over u, f_hat (tangent plane), omega" << (model.top.has_rotor ? ", nu" : "")
            << ":\n  zero (free spin)  " << complex_text(r.zero) << "\n  precession        "
            << complex_text(r.modes.precession) << " (and conjugate)\n  nutation          "
            << complex_text(r.modes.nutation) << " (and conjugate)\n";
  for (const Eigenvalue& v : r.modes.friction) (*report) << "  friction          " << complex_text(v) << "\n";
  for (const Eigenvalue& v : r.modes.bearing) (*report) << "  bearing           " << complex_text(v) << "\n";
  (*report) << "stable: " << (r.stable ? "yes" : "no") << " (largest Re but the zero one " << r.max_real
            << " 1/s; stable below -1e-7)\n";
  (*report) << "relaxation time 1/|Re precession|: " << r.relaxation_time << " s"
            << (r.modes.precession.real() > 0.0 ? " (a growth time: Re precession > 0)" : "") << "\n";
  (*report) << "finite-difference error of Re precession (step h against 2h): " << r.precession_error << " 1/s"
            << (r.resolved ? "" : "  WARNING: above 1 % of Re precession, not resolved in double precision") << "\n";
  if (r.residual > 1e-3)
    (*report) << "note: the state is not an equilibrium (|F| = " << r.residual << ")"
              << (model.top.has_rotor ? ": the rotor's bearing drags the spin" : "")
              << "; this is the spectrum of the frozen state\n";
}

using Json = nlohmann::ordered_json;

Json pair_json(Eigenvalue v) { return {v.real(), v.imag()}; }

Json pairs_json(const std::vector<Eigenvalue>& values) {
  Json a = Json::array();
  for (const Eigenvalue& v : values) a.push_back(pair_json(v));
  return a;
}

// The analysis as JSON (docs/interfaces.md); a number that is not finite is null.
std::string analysis_json(const StabilityResult& r, std::optional<SpinningState> state) {
  Json o = Json::object();
  if (state) o["state"] = top_sim::to_string(*state);
  o["eigenvalues"] = pairs_json(r.eigenvalues);
  o["modes"] = {{"precession", pair_json(r.modes.precession)},
                {"nutation", pair_json(r.modes.nutation)},
                {"friction", pairs_json(r.modes.friction)}};
  o["stable"] = r.stable;
  o["relaxation_time"] = r.relaxation_time;
  o["spin"] = r.spin;
  o["alpha"] = r.alpha;
  return o.dump(2) + "\n";
}

bool write_text(const std::string& path, const std::string& text, const std::string& flag) {
  if (path == "-") {
    std::cout << text << std::flush;
    return static_cast<bool>(std::cout);
  }
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) std::cerr << "top_sim_stability: " << flag << " = '" << path << "': cannot write\n";
  return static_cast<bool>(out);
}

// One row of a sweep: the table on stdout and the plot's CSV.
struct SweepRow {
  const char* sweep;
  StabilityResult r;
};

double max_friction_real(const StabilityResult& r) {
  double m = -INFINITY;
  for (const Eigenvalue& v : r.modes.friction) m = std::max(m, v.real());
  return m;
}

void print_row(const StabilityResult& r, double parameter) {
  (*report) << std::setprecision(6) << std::setw(12) << parameter;
  if (!r.exists) {
    (*report) << "  no sleeping state: " << r.reason << "\n";
    return;
  }
  (*report) << std::setw(11) << r.slip << std::setw(14) << r.modes.precession.real() << std::setw(11)
            << r.modes.precession.imag() << std::setw(13) << r.modes.nutation.real() << std::setw(11)
            << r.modes.nutation.imag() << std::setw(14) << max_friction_real(r) << std::setw(8)
            << (r.stable ? "yes" : "no") << std::setw(13) << r.relaxation_time << (r.resolved ? "" : "  (unresolved)")
            << "\n";
}

void print_header(const char* parameter) {
  (*report) << std::setw(12) << parameter << std::setw(11) << "s*" << std::setw(14) << "Re_prec" << std::setw(11)
            << "Im_prec" << std::setw(13) << "Re_nut" << std::setw(11) << "Im_nut" << std::setw(14) << "maxRe_fric"
            << std::setw(8) << "stable" << std::setw(13) << "relax_time" << "\n";
}

std::vector<SweepRow> sweep_alpha(const top_sim::Scene& scene, double spin, const Range& range) {
  std::vector<SweepRow> rows;
  (*report) << "\nsweep over alpha [rad] at shell spin " << spin << " rad/s (eigenvalues in 1/s, times in s):\n";
  print_header("alpha");
  for (int i = 0; i < range.count; ++i) {
    const double alpha = range.count == 1 ? range.from : range.from + (range.to - range.from) * i / (range.count - 1);
    top_sim::Model m = scene.model;
    m.plane = top_sim::make_plane(alpha, m.plane.gravity);
    rows.push_back({"alpha", top_sim::sleeping_stability(m, spin, scene.initial.rotor_spin)});
    print_row(rows.back().r, alpha);
  }
  return rows;
}

// alpha_c from the eigenvalue crossing, next to the analytic values; returns the located alpha_c (NaN if none).
double report_alpha_c(const top_sim::Scene& scene, double spin, double alpha0) {
  top_sim::Model m = scene.model;
  m.plane = top_sim::make_plane(alpha0, m.plane.gravity);
  const top_sim::StabilityCrossing c = top_sim::locate_stability_loss(m, spin, scene.initial.rotor_spin);
  (*report) << std::setprecision(10);
  if (c.found)
    (*report) << "alpha_c located (stability lost along the slip branch from alpha " << alpha0 << ", " << c.bisections
              << " bisections in s): s = " << c.slip << ", alpha = " << c.alpha << " rad; the crossing mode: "
              << c.mode << " (" << complex_text(c.eigenvalue) << " 1/s at the first unstable slip of the scan)\n";
  else
    (*report) << "alpha_c not located: " << c.reason << "\n";
  (*report) << "alpha_c analytic (critical_inclination, stationary.hpp): " << top_sim::critical_inclination(m.friction)
            << " rad";
  if (m.friction.kind == top_sim::FrictionLawKind::paper)
    (*report) << "; atan(mu_c) = " << std::atan(m.friction.mu_c) << " rad; s_c = " << m.friction.s_c;
  (*report) << "\n";
  return c.found ? c.alpha : NAN;
}

// The sleeping state's sweep over the shell spin, or a tippe top's spinning `state`'s.
std::vector<SweepRow> sweep_spin(const top_sim::Scene& scene, const Range& range, std::optional<SpinningState> state) {
  std::vector<SweepRow> rows;
  (*report) << "\nsweep over the shell spin [rad/s] ";
  if (state) (*report) << "of the spinning " << top_sim::to_string(*state) << " state";
  else (*report) << "at alpha " << scene.model.plane.inclination << " rad";
  if (scene.model.top.has_rotor) (*report) << ", rotor at " << scene.initial.rotor_spin << " rad/s";
  (*report) << " (eigenvalues in 1/s, times in s):\n";
  print_header("spin");
  for (int i = 0; i < range.count; ++i) {
    const double w = range.count == 1 ? range.from : range.from + (range.to - range.from) * i / (range.count - 1);
    if (state)
      rows.push_back({top_sim::to_string(*state),
                      top_sim::spinning_stability(scene.model, *state, w, scene.initial.rotor_spin)});
    else
      rows.push_back({"spin", top_sim::sleeping_stability(scene.model, w, scene.initial.rotor_spin)});
    print_row(rows.back().r, w);
  }
  return rows;
}

// Prints the windows; returns them as "lo:hi,lo:hi" for the plot.
std::string windows_text(const std::vector<top_sim::SpinWindow>& windows, const char* what) {
  (*report) << std::setprecision(10) << "spin windows where " << what << " > 0 (edges bisected):";
  std::string list;
  for (const auto& w : windows) {
    (*report) << " [" << w.lower << ", " << w.upper << "] (largest " << w.max_real << " 1/s at " << w.at_spin << ")";
    list += (list.empty() ? "" : ",") + format_number(w.lower) + ":" + format_number(w.upper);
  }
  (*report) << (windows.empty() ? " none" : "") << "\n";
  return list;
}

// The windows where the watched real part is > 0; returned as "lo:hi,lo:hi" for the plot.
std::string report_windows(const top_sim::Scene& scene, const Range& range, top_sim::WatchedMode watched,
                           const char* what) {
  return windows_text(
      top_sim::unstable_spin_windows(scene.model, scene.initial.rotor_spin, range.from, range.to, range.count, watched),
      what);
}

// A tippe top's spinning state: where the largest Re but the zero one is > 0, and Magnus' critical spin.
std::string report_spinning_windows(const top_sim::Scene& scene, const Range& range, SpinningState state) {
  (*report) << magnus_text(scene.model, state) << "\n" << top_sim::to_string(state) << ": ";
  return windows_text(top_sim::unstable_spin_windows(scene.model, state, scene.initial.rotor_spin, range.from, range.to,
                                                     range.count, top_sim::WatchedMode::any),
                      "the largest Re but the zero one");
}

void write_sweep_csv(std::ostream& os, const std::vector<SweepRow>& rows) {
  os << "sweep,alpha,spin,exists,stable,prec_re,prec_im,nut_re,nut_im,fric_re_max,fric_re_min,max_real\n";
  for (const SweepRow& row : rows) {
    const StabilityResult& r = row.r;
    double fric_min = INFINITY;
    for (const Eigenvalue& v : r.modes.friction) fric_min = std::min(fric_min, v.real());
    os << row.sweep << "," << format_number(r.alpha) << "," << format_number(r.spin) << "," << r.exists << ","
       << r.stable;
    if (!r.exists) {
      os << ",nan,nan,nan,nan,nan,nan,nan\n";
      continue;
    }
    for (double v : {r.modes.precession.real(), r.modes.precession.imag(), r.modes.nutation.real(),
                     r.modes.nutation.imag(), max_friction_real(r), fric_min, r.max_real})
      os << "," << format_number(v);
    os << "\n";
  }
}

// Runs scripts/plots/stability.py; false (after the message) when the PNG was not written.
bool draw(const std::string& csv, const std::string& png, const std::vector<std::string>& extra) {
  report->flush();
  std::vector<std::string> args = {csv, png};
  args.insert(args.end(), extra.begin(), extra.end());
  return top_sim_cli::run_plot("top_sim_stability", "stability.py", args, png);
}

bool load(const std::string& path, top_sim::Scene& scene) {
  try {
    scene = top_sim::load_scene(path);
  } catch (const std::exception& e) {  // SceneError names file, key, value and range
    std::cerr << "top_sim_stability: bad scene: " << e.what() << "\n";
    return false;
  }
  for (const auto& w : scene.warnings) std::cerr << "top_sim_stability: warning: " << w << "\n";
  return true;
}

// The spin sweep: the sleeping state's, or a tippe top's --state (both states without --state); the plot's options.
void run_spin_sweep(const Arguments& args, const top_sim::Scene& scene, std::vector<SweepRow>& rows,
                    std::vector<std::string>& extra) {
  const Range& range = *args.sweep_spin;
  if (!is_tippe_top(scene) && !args.state) {
    const auto spins = sweep_spin(scene, range, std::nullopt);
    rows.insert(rows.end(), spins.begin(), spins.end());
    extra.push_back("--nutation-windows=" + report_windows(scene, range, top_sim::WatchedMode::nutation, "Re nutation"));
    report_windows(scene, range, top_sim::WatchedMode::any, "the largest Re but the zero one");
    return;
  }
  const std::vector<SpinningState> states =
      args.state ? std::vector<SpinningState>{*args.state}
                 : std::vector<SpinningState>{SpinningState::upright, SpinningState::inverted};
  for (const SpinningState state : states) {
    const auto spins = sweep_spin(scene, range, state);
    rows.insert(rows.end(), spins.begin(), spins.end());
    const std::string name = top_sim::to_string(state);
    extra.push_back("--windows-" + name + "=" + report_spinning_windows(scene, range, state));
    const double wk2 = top_sim::magnus_critical_spin_squared(scene.model, state);
    extra.push_back("--magnus-" + name + "=" + format_number(std::isfinite(wk2) && wk2 > 0.0 ? std::sqrt(wk2) : NAN));
    if (!is_tippe_top(scene) && state == SpinningState::upright) {
      extra.push_back("--critical-upright=" + format_number(report_critical_spin(scene, range)));
      extra.push_back("--maxwell-klein=" + format_number(top_sim::maxwell_klein_critical_spin(scene.model)));
    }
  }
}

// The --state rules (docs/interfaces.md): "" when the arguments fit the scene's top, else the message.
std::string state_argument_error(const Arguments& args, const top_sim::Scene& scene) {
  const std::string f = format_number(scene.model.top.com_offset);
  if (args.state && args.sweep_alpha)
    return "--sweep-alpha: not with --state (a spinning state is an equilibrium on a level plane only)";
  if (!is_tippe_top(scene)) return "";
  if (args.sweep_alpha)
    return "--sweep-alpha: not for a tippe top (top.com_offset = " + f + " m < 0): its spinning states are " +
           "equilibria on a level plane only; use --state upright|inverted and --sweep-spin";
  if (!args.state && (!args.sweep_spin || !args.json_path.empty()))
    return "a tippe top (top.com_offset = " + f + " m < 0) has no sleeping state: give --state upright|inverted " +
           "(--sweep-spin alone sweeps both states)";
  return "";
}

// The sweeps, their reports and the plot; false when the plot could not be written.
bool run_sweeps(const Arguments& args, const top_sim::Scene& scene, double spin) {
  std::vector<SweepRow> rows;
  std::vector<std::string> extra;
  if (args.sweep_alpha) {
    rows = sweep_alpha(scene, spin, *args.sweep_alpha);
    const double located = report_alpha_c(scene, spin, args.sweep_alpha->from);
    const double analytic = top_sim::critical_inclination(scene.model.friction);
    extra.insert(extra.end(), {"--alpha-c=" + format_number(located), "--alpha-c-analytic=" + format_number(analytic)});
  }
  if (args.sweep_spin) run_spin_sweep(args, scene, rows, extra);
  if (args.plot_path.empty()) return true;
  char dir_template[] = "/tmp/top_sim_stability_XXXXXX";
  const char* dir = mkdtemp(dir_template);
  if (!dir) {
    std::cerr << "top_sim_stability: --plot: cannot create a temporary directory\n";
    return false;
  }
  const std::string csv = std::string(dir) + "/sweep.csv";
  std::ofstream out(csv);
  write_sweep_csv(out, rows);
  out.close();
  extra.push_back("--title=" + scene.source);
  const bool ok = out && draw(csv, args.plot_path, extra);
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  if (ok) (*report) << "plot: " << args.plot_path << "\n";
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (const auto done = top_sim_cli::parse_command_line("top_sim_stability", kUsage, parse_arguments, argc, argv, args))
    return *done;
  top_sim::Scene scene;
  if (!load(args.scene_path, scene)) return 2;
  if (top_sim::has_shapes(scene.model)) {  // one sphere in top.shapes is the tip sphere and has_shapes is false
    std::cerr << "top_sim_stability: top.shapes: a body with a rim or with two shapes is not analysed (physics.md "
                 "sections 10 and 13: the linear stability covers a tip sphere only, whose sleeping state a second "
                 "shape could touch)\n";
    return 2;
  }
  const double spin = args.spin.value_or(scene.initial.spin);
  if (spin == 0.0) {
    std::cerr << "top_sim_stability: the scene's initial.spin is 0: give a nonzero --spin\n";
    return 2;
  }
  if (const std::string why = state_argument_error(args, scene); !why.empty()) {
    std::cerr << "top_sim_stability: " << why << "\n" << kUsage;
    return 2;
  }
  if (args.json_path == "-") report = &std::cerr;
  (*report) << "scene: " << scene.source << "\n";
  if (is_tippe_top(scene) && !args.state) return run_sweeps(args, scene, spin) ? 0 : 1;  // both states' sweeps
  const StabilityResult r =
      args.state ? top_sim::spinning_stability(scene.model, *args.state, spin, scene.initial.rotor_spin)
                 : top_sim::sleeping_stability(scene.model, spin, scene.initial.rotor_spin);
  bool written = true;
  if (r.exists) {
    print_analysis(scene.model, r, args.state);
    if (!args.json_path.empty()) written = write_text(args.json_path, analysis_json(r, args.state), "--json");
  } else {
    std::cerr << "top_sim_stability: no " << (args.state ? "spinning " + std::string(top_sim::to_string(*args.state)) : "sleeping")
              << " state to analyse at alpha " << format_number(r.alpha) << " rad, spin " << format_number(spin)
              << " rad/s: " << r.reason << "\n";
  }
  written = run_sweeps(args, scene, spin) && written;
  if (!r.exists) return 3;
  return written ? 0 : 1;
}
