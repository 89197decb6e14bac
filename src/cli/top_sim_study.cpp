// top_sim_study [--config DIR] [--out DIR] [--quick] STUDY...   (STUDY: work-precision stability model-choice
// default-choice mujoco all). Writes docs/data/perf_*.csv for scripts/perf/*.py and docs/performance.md.
// Speed against accuracy (issue 5): every run is timed in thread CPU seconds; errors are against a tight reference.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "command_line.hpp"
#include "run.hpp"
#include "top_sim/adiabatic.hpp"
#include "top_sim/plane.hpp"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/stationary.hpp"

namespace {

using namespace top_sim;

double wrap(double a) { return std::remainder(a, 2.0 * M_PI); }

struct Outcome {
  bool ok = false;              // no fault up to T
  std::string fault;
  double t_end = 0.0;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  // contact point at T
  double phi_measured = NAN;    // travel direction over the last 20 % of the run
  double phi_star = NAN;
  double residual = NAN;        // max |E + W - E0| / scale over the run
  double cpu = 0.0;             // CPU seconds of one run
  std::uint64_t steps = 0, rhs = 0;
};

// One run of `scene` to T; short runs are repeated until 50 ms of CPU so their time is not clock noise.
Outcome run_scene(const Scene& scene, double T, bool timed = true) {
  Outcome o;
  int reps = 0;
  double total = 0.0;
  do {
    Simulator sim(scene);
    const double c0 = thread_cpu_seconds();
    sim.advance_to(0.8 * T);
    const Eigen::Vector2d mark = position(sim.state());
    sim.advance_to(T);
    total += thread_cpu_seconds() - c0;
    ++reps;
    if (reps > 1) continue;
    const Snapshot s = sim.snapshot();
    o.ok = !sim.stopped();  // a fault or an end (a fall) has no drift to measure
    o.fault = sim.fault() != ContactFault::none ? to_string(sim.fault())
              : sim.end_state() != EndState::none ? to_string(sim.end_state())
                                                  : "";
    o.t_end = sim.time();
    o.p = position(sim.state());
    const Eigen::Vector2d d = o.p - mark;
    if (o.ok && d.norm() > 0.0) o.phi_measured = travel_angle(d.x(), d.y());
    if (s.has_stationary_state) o.phi_star = s.phi_star;
    o.residual = sim.max_energy_residual();
    o.steps = sim.stats().steps;
    o.rhs = sim.stats().rhs_evaluations;
    if (!o.ok) break;
  } while (timed && total < 0.05 && reps < 1000);
  o.cpu = total / reps;
  return o;
}

std::string g(double v) {
  if (!std::isfinite(v)) return "nan";
  std::ostringstream os;
  os << std::setprecision(6) << v;
  return os.str();
}

struct Options {
  std::string config, out;
  bool quick = false;
};

Scene load(const Options& opt, const std::string& name) { return load_scene(opt.config + "/scenes/" + name + ".yaml"); }

Scene with(Scene s, Method m, double dt, double rtol) {
  s.integrator.method = m;
  s.integrator.dt = dt;
  s.integrator.rtol = rtol;
  s.integrator.atol = rtol * 1e-2;
  return s;
}

// The tight reference: dopri5 at rtol 1e-12; its own error is estimated against rtol 1e-11.
struct Reference {
  Outcome o, check;
};
Reference reference(const Scene& scene, double T) {
  Reference r;
  r.o = run_scene(with(scene, Method::dopri5, 1e-5, 1e-12), T, false);
  r.check = run_scene(with(scene, Method::dopri5, 1e-5, 1e-11), T, false);
  return r;
}

// ---- work-precision ---------------------------------------------------------------------------------------

struct StudyScene {
  std::string name;
  Scene scene;
  double T;
  std::vector<double> euler_dt, rk4_dt;
};

std::vector<double> scaled(std::vector<double> v, double k) {
  for (double& x : v) x *= k;
  return v;
}

// A sleeping top at `spin`, knocked `tilt` off its sleeping axis: the start slides at the sleeping velocity, so
// it nutates without the full-slip start (which at 2000 rad/s pumps the nutation until the top lifts off).
Scene perturbed_sleeping(Scene s, double spin, double tilt) {
  const StationaryState st = stationary_state(s.model, spin);
  s.initial.start = StartKind::tilted;
  s.initial.spin = spin;
  s.initial.tilt = tilt;
  s.initial.tilt_azimuth = 0.0;
  if (st.exists) s.initial.velocity = st.velocity;
  return s;
}

std::vector<StudyScene> study_scenes(const Options& opt) {
  std::vector<StudyScene> out;
  const std::vector<double> e = {1e-3, 3e-4, 1e-4, 3e-5, 1e-5};
  const std::vector<double> r = {3e-3, 1e-3, 3e-4, 1e-4};
  out.push_back({"default", load(opt, "default"), 10.0, e, r});
  const Scene fast = perturbed_sleeping(load(opt, "default"), 2000.0, 0.01);  // nutation 3333 rad/s
  out.push_back({"fast_2000", fast, 2.0, {1e-6, 5e-7, 2.5e-7, 1.25e-7}, scaled(r, 0.1)});
  out.push_back({"gyro_reversal", load(opt, "gyro_reversal"), 60.0, {3e-4, 1e-4, 3e-5, 1e-5}, {1e-3, 3e-4, 1e-4, 3e-5}});
  if (opt.quick)
    for (auto& s : out) {
      s.T = std::min(s.T, 2.0);
      s.euler_dt.resize(3);
      s.rk4_dt.resize(3);
    }
  return out;
}

void work_precision(const Options& opt) {
  std::ofstream csv(opt.out + "/perf_work_precision.csv");
  csv << "scene,T,model,method,setting,ok,cpu_per_sim_s,steps_per_sim_s,rhs_per_sim_s,err_pos_truth,err_pos_own,"
         "err_phi_truth,err_phi_own,residual,ref_self_err_pos\n";
  for (const StudyScene& st : study_scenes(opt)) {
    struct Variant {
      std::string name;
      Scene scene;
    };
    std::vector<Variant> variants;
    variants.push_back({"full_constrained", st.scene});
    Scene stat = st.scene;
    stat.model.normal_force = NormalForceModel::static_approximation;
    variants.push_back({"full_static", stat});
    Scene adia = st.scene;
    adia.model.kind = ModelKind::adiabatic;
    adia.model.automatic.enabled = false;  // the reduced model throughout, whatever the scene's kind
    if (adiabatic_validity(adia.model).empty()) variants.push_back({"adiabatic", adia});

    const Reference truth = reference(st.scene, st.T);
    std::cerr << st.name << ": reference " << truth.o.steps << " steps, self error "
              << (truth.o.p - truth.check.p).norm() << " m\n";
    for (const Variant& v : variants) {
      const Reference own = v.name == "full_constrained" ? truth : reference(v.scene, st.T);
      auto row = [&](Method m, const std::string& setting, double dt, double rtol) {
        const Outcome o = run_scene(with(v.scene, m, dt, rtol), st.T);
        const double per = 1.0 / st.T;
        csv << st.name << "," << st.T << "," << v.name << "," << to_string(m) << "," << setting << "," << o.ok << ","
            << g(o.cpu * per) << "," << g(o.steps * per) << "," << g(o.rhs * per) << ","
            << g(o.ok ? (o.p - truth.o.p).norm() : NAN) << "," << g(o.ok ? (o.p - own.o.p).norm() : NAN) << ","
            << g(std::abs(wrap(o.phi_measured - truth.o.phi_measured))) << ","
            << g(std::abs(wrap(o.phi_measured - own.o.phi_measured))) << "," << g(o.residual) << ","
            << g((own.o.p - own.check.p).norm()) << "\n";
        csv.flush();
      };
      const bool full = v.name != "adiabatic";
      if (full) {
        for (double dt : st.euler_dt) row(Method::euler, "dt=" + g(dt), dt, 1e-8);
        for (double dt : st.euler_dt) row(Method::semi_implicit_euler, "dt=" + g(dt), dt, 1e-8);
        for (double dt : st.rk4_dt) row(Method::rk4, "dt=" + g(dt), dt, 1e-8);
      }
      for (double tol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) row(Method::dopri5, "rtol=" + g(tol), 1e-5, tol);
      for (double tol : {1e-6, 1e-8, 1e-10}) row(Method::rosenbrock4, "rtol=" + g(tol), 1e-5, tol);
      for (double tol : {1e-6, 1e-8, 1e-10}) row(Method::switching, "rtol=" + g(tol), 1e-5, tol);
      std::cerr << "  " << v.name << " done\n";
    }
  }
}

// ---- stability map ------------------------------------------------------------------------------------------

constexpr double kStabilityResidual = 1e-2;  // "bounded": energy residual below 1 % of the energy scale

void stability(const Options& opt) {
  std::ofstream csv(opt.out + "/perf_stability.csv");
  csv << "method,spin,window_s,max_stable_dt,capped,nutation_rate\n";
  const Scene base = load(opt, "default");
  const int n_spin = opt.quick ? 5 : 15;
  for (int k = 0; k < n_spin; ++k) {
    const double spin = 0.1 * std::pow(5000.0 / 0.1, static_cast<double>(k) / (n_spin - 1));
    const Scene sc = perturbed_sleeping(base, spin, 0.01);
    // Slow tops fall over (a physical contact fault): judge stability only before the reference falls.
    const Outcome ref = run_scene(with(sc, Method::dopri5, 1e-5, 1e-10), 1.0, false);
    const double window = ref.ok ? 1.0 : 0.9 * ref.t_end;
    const double nutation = base.model.top.inertia_axial * spin / base.model.top.inertia_transverse;
    for (Method m : {Method::euler, Method::semi_implicit_euler, Method::rk4}) {
      // Scan down from 0.1 s in 8 steps per decade: the first bounded step is the largest.
      double found = NAN;
      bool capped = false;  // the largest step tried (20 steps per window) was already bounded: a lower bound
      int first_tried = -1;
      for (int j = 0; j <= 8 * 6; ++j) {
        const double dt = 0.1 * std::pow(10.0, -j / 8.0);
        if (window / dt > 5e6) break;
        if (window / dt < 20) continue;  // at least 20 steps inside the window
        if (first_tried < 0) first_tried = j;
        const Outcome o = run_scene(with(sc, m, dt, 1e-8), window, false);
        if (o.ok && o.residual < kStabilityResidual) {
          found = dt;
          capped = j == first_tried;
          break;
        }
      }
      csv << to_string(m) << "," << g(spin) << "," << g(window) << "," << g(found) << "," << capped << ","
          << g(nutation) << "\n";
      csv.flush();
    }
    std::cerr << "stability: spin " << spin << " done\n";
  }
}

// ---- default choice: phi* after the whole relaxation ----------------------------------------------------------

void default_choice(const Options& opt) {
  std::ofstream csv(opt.out + "/perf_default_choice.csv");
  csv << "scene,T,method,rtol,ok,cpu_s,real_time_factor,steps,rhs,phi_err,residual\n";
  const double T = opt.quick ? 30.0 : 300.0;
  for (const std::string start : {"tilted", "stationary"}) {
    Scene sc = load(opt, "default");
    if (start == "stationary") sc.initial.start = StartKind::stationary;
    for (Method m : {Method::dopri5, Method::switching, Method::rosenbrock4})
      for (double tol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
        if (m == Method::rosenbrock4 && start == "tilted" && tol < 1e-8) continue;  // seconds of CPU, no news
        const Outcome o = run_scene(with(sc, m, 1e-4, tol), T);
        csv << "default_" << start << "," << T << "," << to_string(m) << "," << g(tol) << "," << o.ok << ","
            << g(o.cpu) << "," << g(T / o.cpu) << "," << o.steps << "," << o.rhs << ","
            << g(std::abs(wrap(o.phi_measured - o.phi_star))) << "," << g(o.residual) << "\n";
        csv.flush();
      }
  }
  // The 10 s transient at the default settings (target: >= 1000x real time at rtol 1e-8).
  for (Method m : {Method::dopri5, Method::switching}) {
    const Outcome o = run_scene(with(load(opt, "default"), m, 1e-4, 1e-8), 10.0);
    csv << "default_tilted," << 10 << "," << to_string(m) << ",1e-08," << o.ok << "," << g(o.cpu) << ","
        << g(10.0 / o.cpu) << "," << o.steps << "," << o.rhs << ",nan," << g(o.residual) << "\n";
  }
}

// ---- MuJoCo comparison ------------------------------------------------------------------------------------------

void mujoco(const Options& opt) {
  std::ofstream csv(opt.out + "/perf_mujoco.csv");
  csv << "method,setting,cpu_per_sim_s,err_pos_m\n";
  // Issue 5's scene: the aluminium top, alpha 0.1, tilt 0.1, 200 rad/s, frictionless, 5 s.
  Scene sc = load(opt, "default");
  sc.model.friction = FrictionLaw{};
  sc.model.friction.kind = FrictionLawKind::coulomb;
  sc.model.friction.mu = 0.0;
  const double T = 5.0;
  const Reference ref = reference(sc, T);
  std::cerr << "mujoco: reference self error " << (ref.o.p - ref.check.p).norm() << " m\n";
  auto row = [&](Method m, const std::string& setting, double dt, double rtol) {
    const Outcome o = run_scene(with(sc, m, dt, rtol), T);
    csv << to_string(m) << "," << setting << "," << g(o.cpu / T) << "," << g(o.ok ? (o.p - ref.o.p).norm() : NAN)
        << "\n";
  };
  for (double dt : {1e-2, 8e-3, 7e-3, 6e-3, 5e-3, 3e-3, 2e-3, 1e-3, 5e-4}) row(Method::rk4, "dt=" + g(dt), dt, 1e-8);
  for (double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) row(Method::dopri5, "rtol=" + g(tol), 1e-4, tol);
}

// ---- model choice per shipped scene -----------------------------------------------------------------------------

void model_choice(const Options& opt) {
  std::ofstream csv(opt.out + "/perf_model_choice.csv");
  csv << "scene,T,choice,model,method,rtol,ok,cpu_s,err_pos_m,err_phi_rad,residual\n";
  for (const std::string name : {"default", "reversed_spin", "supercritical", "upright", "gyro_reversal"}) {
    const Scene base = load(opt, name);
    const double T = opt.quick ? std::min(base.duration, 10.0) : base.duration;
    const Reference ref = reference(base, T);
    auto row = [&](const std::string& choice, Scene s) {
      const Outcome o = run_scene(s, T);
      const std::string model = std::string(kind_name(s.model)) + "/" + to_string(s.model.normal_force);
      csv << name << "," << T << "," << choice << "," << model << "," << to_string(s.integrator.method) << ","
          << g(s.integrator.rtol) << "," << o.ok << "," << g(o.cpu) << ","
          << g(o.ok ? (o.p - ref.o.p).norm() : NAN) << "," << g(std::abs(wrap(o.phi_measured - ref.o.phi_measured)))
          << "," << g(o.residual) << "\n";
      csv.flush();
    };
    row("as shipped", base);
    Scene s = base;
    s.model.normal_force = NormalForceModel::static_approximation;
    row("static normal force", s);
    s = base;
    s.model.kind = ModelKind::adiabatic;
    s.model.automatic.enabled = false;
    if (adiabatic_validity(s.model).empty()) row("adiabatic", s);
    for (Method m : {Method::switching, Method::rosenbrock4})
      if (m != base.integrator.method) row("integrator", with(base, m, base.integrator.dt, base.integrator.rtol));
    row("looser rtol 1e-6", with(base, base.integrator.method, base.integrator.dt, 1e-6));
    std::cerr << "model-choice: " << name << " done\n";
  }
}

const char* kUsage =
    "usage: top_sim_study [--config DIR] [--out DIR] [--quick] STUDY...\n"
    "  STUDY: work-precision | stability | default-choice | mujoco | model-choice | all\n"
    "  --config DIR  tops/, planes/, scenes/ (default: $TOP_SIM_CONFIG_DIR or the installed share/top_sim/config)\n"
    "  --out DIR     where perf_*.csv go (default: .)\n"
    "  --quick       shorter runs and fewer points (a smoke run, not for the report)\n";

struct Arguments {
  Options opt;
  std::vector<std::string> studies;
};

// Reads the command line (throws top_sim_cli::BadArgument); false when it asked for --help.
bool parse_arguments(int argc, char** argv, Arguments& args) {
  std::vector<std::string> names;
  top_sim_cli::CommandLine line("unknown argument");
  line.value("--config", [&](const std::string& v) { args.opt.config = v; })
      .value("--out", [&](const std::string& v) { args.opt.out = v; })
      .flag("--quick", [&] { args.opt.quick = true; })
      .positionals(names);
  if (!line.parse(argc, argv)) return false;
  const std::vector<std::string> every = {"work-precision", "stability", "default-choice", "mujoco", "model-choice"};
  for (const std::string& a : names) {
    if (a == "all") args.studies = every;  // the studies before it are in every already
    else if (std::find(every.begin(), every.end(), a) != every.end()) args.studies.push_back(a);
    else throw top_sim_cli::BadArgument{"unknown argument '" + a + "'"};
  }
  if (args.studies.empty()) throw top_sim_cli::BadArgument{"no study given"};
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  args.opt.config = default_config_dir();
  args.opt.out = ".";
  if (const auto done = top_sim_cli::parse_command_line("top_sim_study", kUsage, parse_arguments, argc, argv, args))
    return *done;
  const Options& opt = args.opt;
  const std::vector<std::string>& studies = args.studies;
  const std::map<std::string, std::function<void(const Options&)>> run = {
      {"work-precision", work_precision}, {"stability", stability}, {"default-choice", default_choice},
      {"mujoco", mujoco}, {"model-choice", model_choice}};
  try {
    for (const auto& s : studies) run.at(s)(opt);
  } catch (const SceneError& e) {
    std::cerr << "top_sim_study: bad scene: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
