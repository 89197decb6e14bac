// peer_mujoco [--config DIR] [--reps N] [--csv FILE] [--mjcf] [--check] [--softness]
// MuJoCo side by side (issue 21 item 5): the frictionless top of config/scenes/frictionless.yaml over a MuJoCo RK4
// dt ladder and a top_sim dopri5 rtol ladder, timed interleaved in this one thread (CPU time, median of --reps),
// errors against top_sim's own dopri5 at rtol 1e-12; prints the CPU ratio at equal or better contact-point error.
// Error: the largest in-plane distance of the contact point from the reference's over the samples every 10 ms of the
// 5 s (501 instants); the error at 5 s alone is printed too. --check runs the cheap assertions of the ctest smoke test;
// --softness splits MuJoCo's error into step and soft contact; --mjcf prints the model.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "mujoco_top.hpp"
#include "top_sim/format.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"

namespace {

using top_sim::Scene;
using Path = std::vector<Eigen::Vector2d>;

constexpr double kT = 5.0;          // simulated time [s]
constexpr double kInterval = 0.01;  // sample spacing [s], a multiple of every MuJoCo dt below
const std::vector<double> kMujocoDt = {5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3};
// Fine where the MuJoCo errors fall, so that "the cheapest top_sim run at equal or better error" is not a coarse pick.
const std::vector<double> kRtol = {1e-2, 5e-3, 3e-3, 2e-3, 1.5e-3, 1e-3, 7e-4, 5e-4, 3e-4, 2e-4, 1e-4,
                                   5e-5, 3e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6, 1e-7, 1e-8};
constexpr double kResolved = 0.1;  // the nutation counts as resolved where the error is below this share of its size

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// dopri5 at rtol, atol = rtol / 100 (the convention of top_sim_study's ladders).
Scene with_rtol(Scene s, double rtol) {
  s.integrator.method = top_sim::Method::dopri5;
  s.integrator.rtol = rtol;
  s.integrator.atol = 1e-2 * rtol;
  return s;
}

// The contact point every kInterval (advance_to reads dopri5's dense output: the steps are those of one advance).
Path top_sim_path(const Scene& s, double interval = kInterval) {
  top_sim::Simulator sim(s);
  Path p{sim.snapshot().contact_point.head<2>()};
  const long n = std::lround(kT / interval);
  for (long k = 1; k <= n; ++k) {
    sim.advance_to(static_cast<double>(k) * interval);
    if (sim.fault() != top_sim::ContactFault::none) throw std::runtime_error("top_sim: " + sim.fault_message());
    p.push_back(sim.snapshot().contact_point.head<2>());
  }
  return p;
}

// The run without samples in between: what the integration itself costs.
double top_sim_final_run(const Scene& s) {
  top_sim::Simulator sim(s);
  sim.advance_to(kT);
  return sim.state()[0];
}

double max_distance(const Path& a, const Path& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) e = std::max(e, (a[i] - b[i]).norm());
  return a.size() == b.size() ? e : NAN;
}

struct Reference {
  Path path;
  double self_error_1e11 = NAN, self_error_half = NAN;  // against rtol 1e-11 and 5e-13
  double nutation_pp = NAN;  // f (theta_max - theta_min): the nutation's size in the contact point [m]
};

double nutation_peak_to_peak(const Scene& s) {
  top_sim::Simulator sim(s);
  double lo = 10.0, hi = -10.0;
  for (long k = 1; k <= std::lround(kT / 1e-4); ++k) {  // about 190 samples per 19 ms nutation period
    sim.advance_to(static_cast<double>(k) * 1e-4);
    const double theta = std::acos(std::clamp(sim.snapshot().figure_axis.z(), -1.0, 1.0));
    lo = std::min(lo, theta);
    hi = std::max(hi, theta);
  }
  return s.model.top.com_offset * (hi - lo);
}

Reference reference(const Scene& base) {
  Reference r;
  r.path = top_sim_path(with_rtol(base, 1e-12));
  r.self_error_1e11 = max_distance(top_sim_path(with_rtol(base, 1e-11)), r.path);
  r.self_error_half = max_distance(top_sim_path(with_rtol(base, 5e-13)), r.path);
  r.nutation_pp = nutation_peak_to_peak(with_rtol(base, 1e-12));
  return r;
}

// One rung of a ladder: its errors once, its CPU times per repetition.
struct Rung {
  bool mujoco = false;
  double setting = 0.0;  // dt or rtol
  double err_max = NAN, err_final = NAN, penetration = NAN;
  long steps = 0, switches = 0;  // top_sim: steps and contact-mode switches (spurious hops of a loose rtol)
  std::vector<double> cpu, cpu_to_T;  // per repetition [s]: the sampled run; top_sim also without samples
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Mean CPU of `fn` over enough calls to fill `min_seconds` (short runs would be clock noise).
template <class Fn>
double cpu_of(Fn&& fn, double min_seconds = 0.02) {
  int calls = 0;
  const double c0 = thread_cpu();
  double elapsed = 0.0;
  do {
    fn();
    ++calls;
    elapsed = thread_cpu() - c0;
  } while (elapsed < min_seconds);
  return elapsed / calls;
}

void error_of(Rung& r, const Scene& base, peer::MujocoTop& mj, const Reference& ref) {
  Path p;
  if (r.mujoco) {
    mj.set_timestep(r.setting);
    p = mj.run(kT, kInterval);
    r.penetration = mj.max_penetration();
    r.steps = std::lround(kT / r.setting);
  } else {
    const Scene s = with_rtol(base, r.setting);
    try {
      p = top_sim_path(s);
    } catch (const std::runtime_error& e) {  // a loose rtol may end in a fault: the rung is left out, said why
      std::cerr << "rtol " << r.setting << ": " << e.what() << "\n";
      return;
    }
    top_sim::Simulator sim(s);
    sim.advance_to(kT);
    r.steps = static_cast<long>(sim.stats().steps);
    r.switches = static_cast<long>(sim.mode_switch_count());
    // The timed run without samples must be the sampled run: dopri5's steps do not depend on the samples.
    if (sim.snapshot().contact_point.head<2>() != p.back())
      std::cerr << "rtol " << r.setting << ": the run without samples ends elsewhere than the sampled run ("
                << sim.mode_switch_count() << " contact-mode switches, max energy residual "
                << sim.max_energy_residual() << ")\n";
  }
  const bool finite = std::all_of(p.begin(), p.end(), [](const Eigen::Vector2d& x) { return x.allFinite(); });
  r.err_max = finite ? max_distance(p, ref.path) : NAN;
  r.err_final = finite && p.size() == ref.path.size() ? (p.back() - ref.path.back()).norm() : NAN;
}

void time_once(Rung& r, const Scene& base, peer::MujocoTop& mj) {
  if (r.mujoco) {
    mj.set_timestep(r.setting);
    r.cpu.push_back(cpu_of([&] { mj.run(kT, kInterval); }));
    return;
  }
  const Scene s = with_rtol(base, r.setting);
  r.cpu.push_back(cpu_of([&] { top_sim_path(s); }));
  r.cpu_to_T.push_back(cpu_of([&] { top_sim_final_run(s); }));
}

Rung rung(bool mujoco, double setting) {
  Rung r;
  r.mujoco = mujoco;
  r.setting = setting;
  return r;
}

std::vector<Rung> ladder() {
  std::vector<Rung> rungs;
  for (double dt : kMujocoDt) rungs.push_back(rung(true, dt));
  for (double rtol : kRtol) rungs.push_back(rung(false, rtol));
  return rungs;
}

// Repetition by repetition, MuJoCo and top_sim rungs alternate, so the machine's load falls on both alike.
void time_interleaved(std::vector<Rung>& rungs, const Scene& base, peer::MujocoTop& mj, int reps) {
  std::vector<Rung*> order;
  for (std::size_t i = 0; i < std::max(kMujocoDt.size(), kRtol.size()); ++i) {
    if (i < kMujocoDt.size()) order.push_back(&rungs[i]);
    if (i < kRtol.size()) order.push_back(&rungs[kMujocoDt.size() + i]);
  }
  for (int rep = 0; rep < reps; ++rep) {
    for (Rung* r : order)
      if (std::isfinite(r->err_max)) time_once(*r, base, mj);
    std::cerr << "repetition " << rep + 1 << "/" << reps << " done\n";
  }
}

// The cheapest top_sim rung (median CPU to 5 s without samples) with err_max <= err; nullptr if none.
const Rung* cheapest_at(const std::vector<Rung>& rungs, double err) {
  const Rung* best = nullptr;
  for (const Rung& r : rungs)
    if (!r.mujoco && r.err_max <= err && (!best || median(r.cpu_to_T) < median(best->cpu_to_T))) best = &r;
  return best;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void print_rungs(const std::vector<Rung>& rungs, const Reference& ref) {
  std::printf("| peer | setting | steps | max error [mm] | error at 5 s [mm] | error / nutation | CPU [ms] | "
              "CPU to 5 s, no samples [ms] | max penetration [mm] / mode switches |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  for (const Rung& r : rungs) {
    if (!std::isfinite(r.err_max)) {
      std::printf("| %s | %s %g | fault (see above) | | | | | | |\n", r.mujoco ? "MuJoCo RK4" : "top_sim dopri5",
                  r.mujoco ? "dt" : "rtol", r.setting);
      continue;
    }
    std::printf("| %s | %s %g | %ld | %s | %s | %s | %s | %s | %s |\n", r.mujoco ? "MuJoCo RK4" : "top_sim dopri5",
                r.mujoco ? "dt" : "rtol", r.setting, r.steps, fmt("%.3g", 1e3 * r.err_max).c_str(),
                fmt("%.3g", 1e3 * r.err_final).c_str(), fmt("%.2g", r.err_max / ref.nutation_pp).c_str(),
                fmt("%.3g", 1e3 * median(r.cpu)).c_str(),
                r.mujoco ? "-" : fmt("%.3g", 1e3 * median(r.cpu_to_T)).c_str(),
                r.mujoco ? fmt("%.3g", 1e3 * r.penetration).c_str() : std::to_string(r.switches).c_str());
  }
}

// "median (min-max)" of the per-repetition ratios a[i] / b[i] (the rungs ran side by side in repetition i).
std::string ratio_text(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) r.push_back(a[i] / b[i]);
  if (r.empty()) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0fx (%.0f-%.0f)", median(r), *std::min_element(r.begin(), r.end()),
                *std::max_element(r.begin(), r.end()));
  return buf;
}

const char* resolved(const Rung& r, const Reference& ref) {
  return r.err_max <= kResolved * ref.nutation_pp ? "yes" : "no";
}

void print_ratios(const std::vector<Rung>& rungs, const Reference& ref) {
  std::printf("\n| MuJoCo dt | its max error [mm] | its CPU [ms] | cheapest top_sim at <= that error | "
              "its max error [mm] | its CPU [ms] to 5 s, no samples (500 samples) | ratio, no samples: median "
              "(min-max) over repetitions | ratio, 500 samples | nutation resolved (MuJoCo / top_sim) |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  for (const Rung& m : rungs) {
    if (!m.mujoco) continue;
    const Rung* t = std::isfinite(m.err_max) ? cheapest_at(rungs, m.err_max) : nullptr;
    if (!t) {
      std::printf("| %g | %s | %s | none | | | | | |\n", m.setting, fmt("%.3g", 1e3 * m.err_max).c_str(),
                  fmt("%.3g", 1e3 * median(m.cpu)).c_str());
      continue;
    }
    std::printf("| %g | %.3g | %.3g | rtol %g | %.3g | %.3g (%.3g) | **%s** | %s | %s / %s |\n", m.setting,
                1e3 * m.err_max, 1e3 * median(m.cpu), t->setting, 1e3 * t->err_max, 1e3 * median(t->cpu_to_T),
                1e3 * median(t->cpu), ratio_text(m.cpu, t->cpu_to_T).c_str(), ratio_text(m.cpu, t->cpu).c_str(),
                resolved(m, ref), resolved(*t, ref));
  }
}

void write_csv(const std::string& file, const std::vector<Rung>& rungs) {
  std::ofstream csv(file);
  csv << "peer,setting,steps,mode_switches,err_max_m,err_final_m,penetration_m,repetition,cpu_s,cpu_to_T_s\n";
  for (const Rung& r : rungs)
    for (std::size_t i = 0; i < r.cpu.size(); ++i)
      csv << (r.mujoco ? "mujoco_rk4" : "top_sim_dopri5") << "," << r.setting << "," << r.steps << "," << r.switches
          << "," << r.err_max << "," << r.err_final << "," << r.penetration << "," << i << "," << r.cpu[i] << ","
          << (r.mujoco ? NAN : r.cpu_to_T[i]) << "\n";
}

// ---- the ctest smoke test: no timing, only agreement -----------------------------------------------------------

bool expect(bool ok, const std::string& what) {
  std::cout << (ok ? "ok    " : "FAIL  ") << what << "\n";
  return ok;
}

bool check_initial_state(const Scene& scene, peer::MujocoTop& mj) {
  using namespace top_sim;
  const StateVector y = initial_state(scene);
  const double alpha = scene.model.plane.inclination;
  const peer::InitialReport r = mj.initial_report();
  const Eigen::Vector3d tip(y[idx::x], y[idx::x + 1], scene.model.top.tip_radius);
  bool ok = expect((r.tip_center_plane - tip).norm() < 1e-12, "MuJoCo's tip sphere starts where top_sim's does");
  ok &= expect((r.figure_axis_world - plane_to_world(alpha, figure_axis(y))).norm() < 1e-12,
               "the body's z axis is top_sim's figure axis (" + fmt("%.3g", std::acos(r.figure_axis_world.z())) +
                   " rad from the world vertical)");
  ok &= expect(r.com_velocity_world.norm() < 1e-12, "the centre of mass starts at rest in MuJoCo");
  ok &= expect((r.omega_world - plane_to_world(alpha, angular_velocity(y))).norm() < 1e-9,
               "MuJoCo's angular velocity is top_sim's (world frame)");
  return ok;
}

// In-plane displacement of the centre of mass along y after kT (frictionless: exactly 0.5 g_y T^2) [m].
double com_slide(const Scene& s) {
  top_sim::Simulator sim(s);
  const Eigen::Vector3d c0 = sim.snapshot().com;
  sim.advance_to(kT);
  return sim.snapshot().com.y() - c0.y();
}

// The contact point slides 0.5 g sin(alpha) T^2 = 12 m downhill and circles the centre of mass at about f sin(0.14)
// = 1.4 mm: a wrong unit, axis or inertia in the mapping shows as mm to m, MuJoCo's soft contact as < 0.1 mm.
int check(const Scene& scene) {
  peer::MujocoTop mj(scene);
  bool ok = check_initial_state(scene, mj);
  const Path ref = top_sim_path(with_rtol(scene, 1e-12));
  const double self = max_distance(top_sim_path(with_rtol(scene, 1e-11)), ref);
  ok &= expect(self < 1e-8, "reference rtol 1e-12 against 1e-11: " + fmt("%.2g", self) + " m (< 1e-8)");
  const double slide = com_slide(with_rtol(scene, 1e-12)), exact = -0.5 * scene.model.plane.gravity *
                                                                   std::sin(scene.model.plane.inclination) * kT * kT;
  ok &= expect(std::abs(slide - exact) < 1e-8, "the reference's centre of mass slid " + fmt("%.10f", slide) +
                                                   " m; 0.5 g sin(alpha) T^2 = " + fmt("%.10f", exact) + " (off by " +
                                                   fmt("%.2g", std::abs(slide - exact)) + " m, < 1e-8)");
  mj.set_timestep(1e-3);
  const double e = max_distance(mj.run(kT, kInterval), ref);
  ok &= expect(e < 2e-4, "MuJoCo RK4 dt 1e-3 agrees with the reference to " + fmt("%.3g", e) + " m (< 0.2 mm)");
  const double loose = max_distance(top_sim_path(with_rtol(scene, 1e-3)), ref);
  const double tight = max_distance(top_sim_path(with_rtol(scene, 1e-6)), ref);
  ok &= expect(tight < loose, "top_sim's error falls with rtol: " + fmt("%.2g", loose) + " m at 1e-3, " +
                                  fmt("%.2g", tight) + " m at 1e-6");
  return ok ? 0 : 1;
}

// Where MuJoCo's error comes from: the step (same contact time constant, smaller dt) or the soft contact (same dt,
// softer contact). Untimed.
int softness(const Scene& scene) {
  const Path ref = top_sim_path(with_rtol(scene, 1e-12));
  peer::MujocoTop mj(scene);
  std::printf("| MuJoCo dt | solref time constant | max error [mm] | max penetration [mm] |\n|---|---|---|---|\n");
  for (double dt : {1e-4, 2e-4, 5e-4, 1e-3})
    for (double tc : {2e-4, 5e-4, 1e-3, 2e-3, 5e-3}) {
      if (tc < 2.0 * dt) continue;
      mj.set_timestep(dt, tc);
      const double e = max_distance(mj.run(kT, kInterval), ref);
      std::printf("| %g | %g | %.3g | %.3g |\n", dt, tc, 1e3 * e, 1e3 * mj.max_penetration());
    }
  return 0;
}

const char* kUsage = "usage: peer_mujoco [--config DIR] [--reps N] [--csv FILE] [--mjcf] [--check] [--softness]";

struct Options {
  std::string config = TOP_SIM_PEER_CONFIG_DIR, csv;
  int reps = 5;
  bool check = false, print_mjcf = false, softness = false;
};

int repetitions(const std::string& text) {
  const std::optional<double> n = top_sim::parse_number(text);
  if (!n || !(*n >= 1.0 && *n <= 1000.0) || *n != std::floor(*n))
    throw std::invalid_argument("--reps: '" + text + "' is not allowed; must be an integer in [1, 1000]");
  return static_cast<int>(*n);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--config" && has_value) o.config = argv[++i];
    else if (a == "--csv" && has_value) o.csv = argv[++i];
    else if (a == "--reps" && has_value) o.reps = repetitions(argv[++i]);
    else if (a == "--check") o.check = true;
    else if (a == "--mjcf") o.print_mjcf = true;
    else if (a == "--softness") o.softness = true;
    else throw std::invalid_argument(kUsage);
  }
  return o;
}

int bench(const Scene& scene, const Options& opt) {
  const Reference ref = reference(scene);
  std::printf("MuJoCo %s; reference: top_sim dopri5 rtol 1e-12; its max distance from rtol 1e-11: %.2g m, from "
              "rtol 5e-13: %.2g m; nutation in the contact point f (theta_max - theta_min) = %.3g mm\n\n",
              mj_versionString(), ref.self_error_1e11, ref.self_error_half, 1e3 * ref.nutation_pp);
  peer::MujocoTop mj(scene);
  std::vector<Rung> rungs = ladder();
  for (Rung& r : rungs) error_of(r, scene, mj, ref);
  time_interleaved(rungs, scene, mj, opt.reps);
  print_rungs(rungs, ref);
  print_ratios(rungs, ref);
  if (!opt.csv.empty()) write_csv(opt.csv, rungs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options opt = parse(argc, argv);
    const Scene scene = top_sim::load_scene(opt.config + "/scenes/frictionless.yaml");
    if (opt.print_mjcf) {
      std::cout << peer::mjcf(scene, 1e-3);
      return 0;
    }
    if (opt.softness) return softness(scene);
    return opt.check ? check(scene) : bench(scene, opt);
  } catch (const std::exception& e) {
    std::cerr << "peer_mujoco: " << e.what() << "\n";
    return 2;
  }
}
