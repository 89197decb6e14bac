#include "sweep_point.hpp"

#include <yaml-cpp/yaml.h>

#include <ctime>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "top_sim/plane.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

namespace {

bool is_yaml_path(const std::string& name) {
  const bool yaml_suffix = name.size() > 5 && name.compare(name.size() - 5, 5, ".yaml") == 0;
  return yaml_suffix || name.find('/') != std::string::npos;
}

// A named file of <config>/<dir>, or a path, as a YAML tree (the scene loader then validates it).
YAML::Node load_named(const std::string& name, const std::string& config_dir, const std::string& dir,
                      const std::string& key) {
  const std::string path = is_yaml_path(name) ? name : config_dir + "/" + dir + "/" + name + ".yaml";
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw SceneError(path, key, "'" + name + "': no such file (a name in " + config_dir + "/" + dir + "/ or a .yaml path)");
  } catch (const YAML::Exception& e) {
    throw SceneError(path, key, std::string("not valid YAML: ") + e.what());
  }
}

double wrapped_difference(double a, double b) { return std::remainder(a - b, 2.0 * M_PI); }

// A number's cell in the sweep CSV (docs/interfaces.md): 10 significant digits, nan when not finite.
std::string csv_cell(double v) {
  if (!std::isfinite(v)) return "nan";
  std::ostringstream os;
  os << std::setprecision(10) << v;
  return os.str();
}

// The scene's contact.patch_radius, only when there is a patch: a point-contact scene stays the file's own.
void set_patch(const PatchRadius& patch, YAML::Node& root) {
  if (patch.hertz) root["contact"]["patch_radius"] = "hertz";
  else if (patch.metres > 0.0) root["contact"]["patch_radius"] = patch.metres;
}

// parse_scene, with a refused patch radius named as the flag that asked for it.
Scene parse_point_scene(const YAML::Node& root, const std::string& source, const std::string& config_dir,
                        const PatchRadius& patch) {
  try {
    return parse_scene(root, source, config_dir);
  } catch (const SceneError& e) {
    if (e.key != "contact.patch_radius") throw;
    const std::string what = e.what(), prefix = e.file + ": " + e.key + ": ";
    const std::string problem = what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what;
    throw SceneError(e.file, e.key, "--patch-radius = '" + patch_radius_text(patch) + "' for this top and plane: " +
                                        problem + " (or give --patch-radius a number >= 0 [m])");
  }
}

}  // namespace

std::string patch_radius_text(const PatchRadius& patch) { return patch.hertz ? "hertz" : csv_cell(patch.metres); }

Scene make_sweep_scene(const SweepPoint& p, const SweepSettings& settings) {
  const std::string config_dir = settings.config_dir.empty() ? default_config_dir() : settings.config_dir;
  YAML::Node root;
  root["top"] = load_named(p.top, config_dir, "tops", "top");
  YAML::Node friction = load_named(p.plane, config_dir, "planes", "friction");
  if (p.mu_c) friction["mu_c"] = *p.mu_c;
  if (p.s_c) friction["s_c"] = *p.s_c;
  root["friction"] = friction;
  root["plane"]["inclination"] = p.alpha;
  root["initial"]["start"] = "tilted";
  root["initial"]["tilt"] = settings.tilt;
  root["initial"]["spin"] = p.spin;
  root["duration"] = settings.max_duration;
  set_patch(p.patch, root);
  std::ostringstream source;
  source << "sweep point (top " << p.top << ", plane " << p.plane << ", alpha " << p.alpha << ", spin " << p.spin;
  if (p.patch.hertz || p.patch.metres > 0.0) source << ", patch_radius " << patch_radius_text(p.patch);
  source << ")";
  Scene scene = parse_point_scene(root, source.str(), config_dir, p.patch);
  if (settings.start == SweepStart::launched) {
    // Start inside the sleeping state's basin: slip near s*, not s = 1 (which runs away close to alpha_c).
    const StationaryState st = stationary_state(scene.model, p.spin);
    if (st.exists) {
      // The initial keys are world-frame.
      const Eigen::Vector3d f_w = plane_to_world(p.alpha, st.f_hat);
      scene.initial.tilt = std::acos(std::clamp(f_w.z(), -1.0, 1.0)) + settings.launch_perturbation;
      scene.initial.tilt_azimuth = std::atan2(f_w.y(), f_w.x());
      scene.initial.velocity = st.velocity;
    }
  }
  return scene;
}

namespace {

// The analytic columns: the paper law's parameters, the stable and unstable roots of mu(s) = tan(alpha).
void fill_analytic(const FrictionLaw& law, double alpha, SweepResult& res) {
  const bool paper = law.kind == FrictionLawKind::paper;
  res.mu_c = paper ? law.mu_c : std::numeric_limits<double>::quiet_NaN();
  res.s_c = paper ? law.s_c : std::numeric_limits<double>::quiet_NaN();
  res.tan_alpha = std::tan(alpha);
  for (const SlipRoot& root : slip_roots(law, res.tan_alpha)) {
    if (root.stable && res.s_stable < 0.0) res.s_stable = root.s;
    else if (!root.stable && res.s_stable >= 0.0 && res.s_unstable < 0.0) res.s_unstable = root.s;
  }
}

struct RunBudget {
  double t_max = 0.0;   // give up after this simulated time [s]
  double window = 1.0;  // phi is measured once per window [s]
};

// The relaxation is a path length: budget time as path / sleeping speed, windows likewise.
RunBudget run_budget(const StationaryState& st, const SweepSettings& settings) {
  RunBudget b;
  b.t_max = settings.slide_duration;
  if (st.exists) {
    const double v = std::hypot(st.rolling_speed, st.sliding_speed);
    b.t_max = v > 0.0 ? std::clamp(settings.max_path / v, settings.min_duration, settings.max_duration)
                      : settings.min_duration;
    b.window = v > 0.0 ? std::clamp(settings.window_path / v, 1.0, b.t_max / 10.0) : b.t_max / 10.0;
  }
  return b;
}

// Runs window by window until the top sleeps with a settled phi, has slid for slide_duration, faults, or the budget
// ends; sets outcome (empty when unconverged), regime, phi and note.
void relax(Simulator& sim, const SweepSettings& settings, const RunBudget& budget, SweepResult& res) {
  std::optional<double> previous_phi;
  int quiet_windows = 0;
  constexpr int kQuietWindows = 3;
  double sliding_since = -1.0;
  while (sim.time() < budget.t_max - 1e-9) {
    const double t_start = sim.time();
    RunOptions opt;
    opt.duration = std::min(budget.window, budget.t_max - t_start);
    const RunResult r = run(sim, opt);
    res.regime = r.final.regime;
    if (r.phi_measured) res.phi = r.phi_measured;
    if (r.final.fault != ContactFault::none) {
      res.outcome = "contact_fault";
      res.note = r.final.fault_message;
      return;
    }
    if (r.final.end_state != EndState::none) {  // the top fell: an end of its story, named as the outcome
      res.outcome = to_string(r.final.end_state);
      res.note = r.final.end_message;
      return;
    }
    if (res.regime == Regime::sliding) {
      if (sliding_since < 0.0) sliding_since = t_start;
      if (sim.time() - sliding_since >= settings.slide_duration - 1e-9) {
        res.outcome = "sliding";
        return;
      }
    } else {
      sliding_since = -1.0;
    }
    // The path still oscillates about phi* (precession): require several small changes in a row, so
    // that windows landing on equal phases of the oscillation cannot fake convergence.
    const bool sleeping = res.regime == Regime::sleeping;
    const double change = previous_phi && r.phi_measured ? std::abs(wrapped_difference(*r.phi_measured, *previous_phi))
                                                         : std::numeric_limits<double>::infinity();
    quiet_windows = sleeping && change < settings.phi_tolerance ? quiet_windows + 1 : 0;
    if (quiet_windows >= kQuietWindows) {
      res.outcome = "sleeping";
      return;
    }
    previous_phi = r.phi_measured;
  }
}

}  // namespace

SweepResult run_sweep_point(const SweepPoint& p, const SweepSettings& settings) {
  SweepResult res;
  res.point = p;
  const Scene scene = make_sweep_scene(p, settings);
  fill_analytic(scene.model.friction, p.alpha, res);

  const double cpu0 = thread_cpu_seconds();
  Simulator sim(scene);
  const StationaryState st = sim.stationary();
  if (st.exists && st.phi_defined) res.phi_star = st.phi;
  relax(sim, settings, run_budget(st, settings), res);
  if (res.outcome.empty()) res.outcome = res.regime == Regime::sliding ? "sliding" : "unconverged";
  if (res.phi) {
    // Negative spin mirrors the path to pi - phi: report the half-angle comparable to s*.
    const double phi = p.spin >= 0.0 ? *res.phi : M_PI - *res.phi;
    res.tan_half = std::tan(0.5 * phi);
  }
  res.cpu_seconds = thread_cpu_seconds() - cpu0;
  res.sim_seconds = sim.time();
  res.steps = sim.stats().steps;
  res.rhs_evaluations = sim.stats().rhs_evaluations;
  return res;
}

void write_sweep_header(std::ostream& os) {
  os << "top,plane,mu_c,s_c,spin,alpha,tan_alpha,s_stable,s_unstable,phi_star,phi_measured,"
        "tan_half_phi_measured,outcome,regime,sim_seconds,cpu_seconds,steps,rhs_evaluations,patch_radius\n";
}

void write_sweep_row(std::ostream& os, const SweepResult& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  os << r.point.top << ',' << r.point.plane << ',';
  for (double v : {r.mu_c, r.s_c, r.point.spin, r.point.alpha, r.tan_alpha, r.s_stable >= 0.0 ? r.s_stable : nan,
                   r.s_unstable >= 0.0 ? r.s_unstable : nan, r.phi_star.value_or(nan), r.phi.value_or(nan),
                   r.tan_half.value_or(nan)})
    os << csv_cell(v) << ',';
  os << r.outcome << ',' << to_string(r.regime) << ',' << csv_cell(r.sim_seconds) << ',' << csv_cell(r.cpu_seconds)
     << ',' << r.steps << ',' << r.rhs_evaluations << ',' << patch_radius_text(r.point.patch) << '\n';
}

}  // namespace top_sim
