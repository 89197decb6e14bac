// peer_mujoco [--config DIR] [--reps N] [--csv FILE] [--mjcf] [--check] [--softness] [--pivot] [--tippe-top]
//             [--euler-disk]
// MuJoCo side by side (issue 21 item 5): the frictionless top of config/scenes/frictionless.yaml over a MuJoCo RK4
// dt ladder, a top_sim dopri5 rtol ladder and top_sim rk4, implicit_midpoint and fitted_midpoint dt ladders, timed
// interleaved in this
// one thread (CPU time, median of --reps), errors against top_sim's own dopri5 at rtol 1e-12; prints the CPU ratio at
// equal or better contact-point error, and how much of the nutation each run keeps.
// Error: the largest in-plane distance of the contact point from the reference's over the samples every 10 ms of the
// 5 s (501 instants; top_sim rk4 and implicit_midpoint: at every step end, where a fixed-step run lands without
// changing its steps); the error at 5 s alone is printed too. Nutation kept: the peak-to-peak of the figure axis's
// tilt from the plane normal over the run's last second, divided by the reference's; phase error: the largest
// difference of that tilt from the reference's at the run's samples in the last second, over the same peak-to-peak
// (about 0 in phase, about 1 out of phase, whatever the frequency). --check runs the cheap
// assertions of the ctest smoke test; --softness splits MuJoCo's error into step and soft contact; --mjcf prints the
// model; --pivot runs the pivoting upright top with condim 4 instead (pivot.cpp); --tippe-top and --euler-disk run
// MuJoCo's tutorial tippe top and Euler's disk (mujoco_shapes.cpp, euler_disk.cpp; with --check: their ctests).
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "mujoco_shapes.hpp"
#include "mujoco_top.hpp"
#include "pivot.hpp"
#include "top_sim/format.hpp"
#include "../../src/core/nutation.hpp"
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
// rk4's stability limit on the imaginary axis is h w = 2 sqrt(2): h = 8.6 ms for the 328 rad/s nutation (9 ms faults).
const std::vector<double> kRk4Dt = {1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3, 7e-3, 8e-3, 8.5e-3, 9e-3};
// The implicit midpoint rule has |R(iy)| = 1: no stability limit, the nutation kept at every step (its frequency
// becomes 2 atan(h w / 2) / h: 10 % slower at h w = 1.1, h = 3.4 ms; its phase costs at most twice the nutation's
// 0.01 mm in the contact point).
const std::vector<double> kMidpointDt = {1e-3, 2e-3,   3e-3,   4e-3, 5e-3,   6e-3, 8e-3,
                                         1e-2, 1.2e-2, 1.5e-2, 2e-2, 2.5e-2, 3e-2};
// fitted_midpoint at k pi / w, w the fast-top nutation frequency: odd k puts the step's midpoint at the nutation's
// centre, even k samples it at the same phase every step (its resonance).
constexpr int kFittedHalfPeriods = 7;
// The largest phase error of a run "in phase" with the nutation: its tilt within a quarter of the nutation's
// peak-to-peak of the reference's (a run without nutation has 0.5, one in antiphase 1).
constexpr double kInPhase = 0.25;
constexpr double kKeptFrom = kT - 1.0;  // the nutation kept is measured over the last second
constexpr double kTiltInterval = 1e-4;  // dense-output samples of the tilt: about 190 per 19 ms nutation period

enum class Peer { mujoco, dopri5, rk4, midpoint, fitted };
constexpr int kPeers = 5;

bool fixed_step(Peer p) { return p == Peer::rk4 || p == Peer::midpoint || p == Peer::fitted; }

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// dopri5 at rtol, atol = rtol / 100 (the convention of top_sim_study's ladders).
Scene with_rtol(Scene s, double rtol) {
  s.integrator.method = top_sim::Method::dopri5;
  s.integrator.rtol = rtol;
  s.integrator.atol = 1e-2 * rtol;
  return s;
}

// dopri5, rk4, implicit_midpoint or fitted_midpoint at the rung's setting (rtol or dt).
Scene configured(const Scene& base, Peer peer, double setting) {
  if (peer == Peer::dopri5) return with_rtol(base, setting);
  Scene s = base;
  s.integrator.method = peer == Peer::rk4        ? top_sim::Method::rk4
                        : peer == Peer::midpoint ? top_sim::Method::implicit_midpoint
                                                 : top_sim::Method::fitted_midpoint;
  s.integrator.dt = setting;
  return s;
}

// k h for k = 1, 2, ... up to `to`, and `to` itself if not on that grid.
std::vector<double> grid(double h, double to, double from = 0.0) {
  std::vector<double> t;
  for (long k = std::lround(std::ceil(from / h - 1e-9)); static_cast<double>(k) * h <= to + 1e-12; ++k)
    if (k > 0) t.push_back(static_cast<double>(k) * h);
  if (t.empty() || t.back() < to - 1e-12) t.push_back(to);
  return t;
}

// Where a top_sim rung is sampled: every kInterval for dopri5 (dense output: the steps do not depend on it), every
// step for rk4 and implicit_midpoint (a fixed-step run lands on multiples of dt with h = dt: the same steps as one
// advance to kT).
std::vector<double> sample_times(Peer peer, double setting) {
  return grid(fixed_step(peer) ? setting : kInterval, kT);
}

double tilt(const top_sim::StateVector& y) { return std::acos(std::clamp(top_sim::figure_axis(y).z(), -1.0, 1.0)); }

// A run advanced to each of `times`: the contact point (if asked: it builds the sample) and the tilt there.
struct Track {
  std::vector<double> t, tilt;
  Path contact;
  long steps = 0;
  top_sim::StateVector end{};
};

Track track(const Scene& s, const std::vector<double>& times, bool contact = true) {
  top_sim::Simulator sim(s);
  Track tr;
  if (contact) tr.contact.push_back(sim.snapshot().contact_point.head<2>());
  for (double t : times) {
    sim.advance_to(t);
    if (sim.fault() != top_sim::ContactFault::none) throw std::runtime_error("top_sim: " + sim.fault_message());
    tr.t.push_back(t);
    tr.tilt.push_back(tilt(sim.state()));
    if (contact) tr.contact.push_back(sim.snapshot().contact_point.head<2>());
  }
  tr.steps = static_cast<long>(sim.stats().steps);
  tr.end = sim.state();
  return tr;
}

// The contact point every kInterval from t = 0 (advance_to reads dopri5's dense output: the steps are those of one
// advance).
Path top_sim_path(const Scene& s) { return track(s, grid(kInterval, kT)).contact; }

// The run without samples in between: what the integration itself costs.
double top_sim_final_run(const Scene& s) {
  top_sim::Simulator sim(s);
  sim.advance_to(kT);
  return sim.state()[0];
}

// Peak-to-peak of the tilt over the samples at t >= kKeptFrom [rad].
double last_second_peak_to_peak(const std::vector<double>& t, const std::vector<double>& tilt) {
  double lo = 10.0, hi = -10.0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= kKeptFrom - 1e-12) {
      lo = std::min(lo, tilt[i]);
      hi = std::max(hi, tilt[i]);
    }
  return hi - lo;
}

// The largest |tilt - the reference's tilt| at the instants t >= kKeptFrom, over the reference's peak-to-peak there:
// about 0 for a run in phase with the nutation, about 1 for one out of phase.
double phase_error(const Scene& base, const std::vector<double>& t, const std::vector<double>& tilt, double ref_pp) {
  std::vector<double> times, run;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= kKeptFrom - 1e-12) {
      times.push_back(t[i]);
      run.push_back(tilt[i]);
    }
  const Track ref = track(with_rtol(base, 1e-12), times, false);
  double e = 0.0;
  for (std::size_t i = 0; i < run.size(); ++i) e = std::max(e, std::abs(run[i] - ref.tilt[i]));
  return e / ref_pp;
}

double max_distance(const Path& a, const Path& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) e = std::max(e, (a[i] - b[i]).norm());
  return a.size() == b.size() ? e : NAN;
}

struct Reference {
  Path path;
  double self_error_1e11 = NAN, self_error_half = NAN;  // against rtol 1e-11 and 5e-13
  double nutation_pp = NAN;  // f (theta_max - theta_min) over the 5 s: the nutation's size in the contact point [m]
  double tilt_pp_last = NAN;  // theta_max - theta_min over the last second [rad]
  double nutation_w = NAN;    // the nutation's angular frequency, from the tilt's period [rad/s]
};

// Angular frequency of the tilt's oscillation: upward crossings of its mid value, linearly interpolated.
double tilt_frequency(const std::vector<double>& t, const std::vector<double>& tilt) {
  const auto [lo, hi] = std::minmax_element(tilt.begin(), tilt.end());
  const double mid = 0.5 * (*lo + *hi);
  double first = NAN, last = NAN;
  long crossings = 0;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (tilt[i - 1] < mid && tilt[i] >= mid) {
      const double tc = t[i - 1] + (t[i] - t[i - 1]) * (mid - tilt[i - 1]) / (tilt[i] - tilt[i - 1]);
      if (crossings++ == 0) first = tc;
      last = tc;
    }
  return 2.0 * M_PI * static_cast<double>(crossings - 1) / (last - first);
}

Reference reference(const Scene& base) {
  Reference r;
  r.path = top_sim_path(with_rtol(base, 1e-12));
  r.self_error_1e11 = max_distance(top_sim_path(with_rtol(base, 1e-11)), r.path);
  r.self_error_half = max_distance(top_sim_path(with_rtol(base, 5e-13)), r.path);
  const Track fine = track(with_rtol(base, 1e-12), grid(kTiltInterval, kT), false);
  const auto [lo, hi] = std::minmax_element(fine.tilt.begin(), fine.tilt.end());
  r.nutation_pp = base.model.top.com_offset * (*hi - *lo);
  r.tilt_pp_last = last_second_peak_to_peak(fine.t, fine.tilt);
  r.nutation_w = tilt_frequency(fine.t, fine.tilt);
  return r;
}

// A dopri5 run's tilt on its dense output every kTiltInterval over the last second (the steps are those of the
// unsampled run: checked, else said).
Track dopri5_last_second(const Scene& s) {
  const Track tr = track(s, grid(kTiltInterval, kT, kKeptFrom), false);
  top_sim::Simulator sim(s);
  sim.advance_to(kT);
  if (static_cast<long>(sim.stats().steps) != tr.steps || sim.state() != tr.end)
    std::cerr << "rtol " << s.integrator.rtol << ": the tilt samples changed the run (" << tr.steps << " steps, "
              << sim.stats().steps << " without)\n";
  return tr;
}

// One rung of a ladder: its errors once, its CPU times per repetition.
struct Rung {
  Peer peer = Peer::mujoco;
  double setting = 0.0;  // dt or rtol
  double err_max = NAN, err_final = NAN, penetration = NAN, kept = NAN, phase = NAN;
  int half_periods = 0;  // fitted_midpoint: dt = half_periods pi / w
  long steps = 0, switches = 0;  // top_sim: steps and contact-mode switches (spurious hops of a loose rtol)
  std::vector<double> cpu, cpu_to_T;  // per repetition [s]: the sampled run; top_sim also without samples
};

const char* peer_name(Peer p) {
  return p == Peer::mujoco   ? "MuJoCo RK4"
         : p == Peer::dopri5 ? "top_sim dopri5"
         : p == Peer::rk4      ? "top_sim rk4"
         : p == Peer::midpoint ? "top_sim implicit_midpoint"
                               : "top_sim fitted_midpoint";
}
const char* csv_name(Peer p) {
  return p == Peer::mujoco   ? "mujoco_rk4"
         : p == Peer::dopri5 ? "top_sim_dopri5"
         : p == Peer::rk4      ? "top_sim_rk4"
         : p == Peer::midpoint ? "top_sim_implicit_midpoint"
                               : "top_sim_fitted_midpoint";
}
const char* method_name(Peer p) {
  return p == Peer::dopri5 ? "dopri5" : p == Peer::rk4 ? "rk4" : p == Peer::midpoint ? "implicit_midpoint" : "fitted_midpoint";
}
std::string setting_text(const Rung& r) {
  if (r.half_periods > 0) return "dt " + fmt("%.4g", r.setting) + " (" + std::to_string(r.half_periods) + " pi / w)";
  return std::string(r.peer == Peer::dopri5 ? "rtol " : "dt ") + fmt("%g", r.setting);
}

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

void mujoco_error(Rung& r, const Scene& base, peer::MujocoTop& mj, const Reference& ref, Path& p) {
  mj.set_timestep(r.setting);
  p = mj.run(kT, kInterval);
  r.penetration = mj.max_penetration();
  r.steps = std::lround(kT / r.setting);
  const std::vector<double> t = grid(r.setting, kT, kKeptFrom), tilt = mj.tilt_run(kT, kKeptFrom);
  r.kept = last_second_peak_to_peak(t, tilt) / ref.tilt_pp_last;
  r.phase = phase_error(base, t, tilt, ref.tilt_pp_last);
}

// The sampled run (every 10 ms for dopri5, every step for the fixed-step methods), its kept nutation, and the
// reference at its samples.
void top_sim_error(Rung& r, const Scene& base, const Reference& ref, Path& p, Path& ref_path) {
  const Scene s = configured(base, r.peer, r.setting);
  const Track tr = track(s, sample_times(r.peer, r.setting));
  p = tr.contact;
  ref_path = fixed_step(r.peer) ? track(with_rtol(base, 1e-12), tr.t).contact : ref.path;
  const Track last = fixed_step(r.peer) ? tr : dopri5_last_second(s);
  r.kept = last_second_peak_to_peak(last.t, last.tilt) / ref.tilt_pp_last;
  r.phase = phase_error(base, last.t, last.tilt, ref.tilt_pp_last);
  top_sim::Simulator sim(s);
  sim.advance_to(kT);
  r.steps = static_cast<long>(sim.stats().steps);
  r.switches = static_cast<long>(sim.mode_switch_count());
  // The timed run without samples must be the sampled run: no method's steps depend on the samples.
  if (r.steps != tr.steps || sim.state() != tr.end)
    std::cerr << peer_name(r.peer) << " " << setting_text(r) << ": the run without samples ends elsewhere than the "
              << "sampled run (" << r.steps << " steps against " << tr.steps << ", " << sim.mode_switch_count()
              << " contact-mode switches, max energy residual " << sim.max_energy_residual() << ")\n";
}

void error_of(Rung& r, const Scene& base, peer::MujocoTop& mj, const Reference& ref) {
  Path p, ref_path = ref.path;
  if (r.peer == Peer::mujoco) {
    mujoco_error(r, base, mj, ref, p);
  } else {
    try {
      top_sim_error(r, base, ref, p, ref_path);
    } catch (const std::runtime_error& e) {  // a loose rtol or a long rk4 step may fault: left out, said why
      std::cerr << peer_name(r.peer) << " " << setting_text(r) << ": " << e.what() << "\n";
      r.kept = NAN;
      return;
    }
  }
  const bool finite = std::all_of(p.begin(), p.end(), [](const Eigen::Vector2d& x) { return x.allFinite(); });
  r.err_max = finite ? max_distance(p, ref_path) : NAN;
  r.err_final = finite && p.size() == ref_path.size() ? (p.back() - ref_path.back()).norm() : NAN;
}

void time_once(Rung& r, const Scene& base, peer::MujocoTop& mj) {
  if (r.peer == Peer::mujoco) {
    mj.set_timestep(r.setting);
    r.cpu.push_back(cpu_of([&] { mj.run(kT, kInterval); }));
    return;
  }
  const Scene s = configured(base, r.peer, r.setting);
  const std::vector<double> times = sample_times(r.peer, r.setting);
  r.cpu.push_back(cpu_of([&] { track(s, times); }));
  r.cpu_to_T.push_back(cpu_of([&] { top_sim_final_run(s); }));
}

Rung rung(Peer peer, double setting, int half_periods = 0) {
  Rung r;
  r.peer = peer;
  r.setting = setting;
  r.half_periods = half_periods;
  return r;
}

std::vector<Rung> ladder(const Scene& scene) {
  const double w = top_sim::fast_top_nutation_frequency(scene.model, top_sim::initial_state(scene));
  std::vector<Rung> rungs;
  for (double dt : kMujocoDt) rungs.push_back(rung(Peer::mujoco, dt));
  for (double rtol : kRtol) rungs.push_back(rung(Peer::dopri5, rtol));
  for (double dt : kRk4Dt) rungs.push_back(rung(Peer::rk4, dt));
  for (double dt : kMidpointDt) rungs.push_back(rung(Peer::midpoint, dt));
  for (int k = 1; k <= kFittedHalfPeriods; ++k) rungs.push_back(rung(Peer::fitted, k * M_PI / w, k));
  return rungs;
}

// Repetition by repetition, MuJoCo and top_sim rungs alternate (one of each ladder in turn), so the machine's load
// falls on all alike.
void time_interleaved(std::vector<Rung>& rungs, const Scene& base, peer::MujocoTop& mj, int reps) {
  std::vector<std::vector<Rung*>> by_peer(kPeers);
  for (Rung& r : rungs) by_peer[static_cast<int>(r.peer)].push_back(&r);
  std::vector<Rung*> order;
  for (std::size_t i = 0; i < rungs.size(); ++i)
    for (const std::vector<Rung*>& l : by_peer)
      if (i < l.size()) order.push_back(l[i]);
  for (int rep = 0; rep < reps; ++rep) {
    for (Rung* r : order)
      if (std::isfinite(r->err_max)) time_once(*r, base, mj);
    std::cerr << "repetition " << rep + 1 << "/" << reps << " done\n";
  }
}

// The cheapest top_sim rung (median CPU to 5 s without samples) with err_max <= err, of the given method or of
// any (Peer::mujoco); nullptr if none.
const Rung* cheapest_at(const std::vector<Rung>& rungs, double err, Peer only) {
  const Rung* best = nullptr;
  for (const Rung& r : rungs)
    if (r.peer != Peer::mujoco && (only == Peer::mujoco || r.peer == only) && r.err_max <= err &&
        (!best || median(r.cpu_to_T) < median(best->cpu_to_T)))
      best = &r;
  return best;
}

void print_rungs(const std::vector<Rung>& rungs, const Reference& ref) {
  std::printf("| peer | setting | steps | max error [mm] | error at 5 s [mm] | error / nutation | nutation kept | "
              "phase error | CPU with samples [ms] | CPU to 5 s, no samples [ms] | max penetration [mm] / mode "
              "switches |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Rung& r : rungs) {
    if (!std::isfinite(r.err_max)) {
      std::printf("| %s | %s | fault (see above) | | | | | | | | |\n", peer_name(r.peer), setting_text(r).c_str());
      continue;
    }
    const bool mj = r.peer == Peer::mujoco;
    std::printf("| %s | %s | %ld | %s | %s | %s | %s | %s | %s | %s | %s |\n", peer_name(r.peer),
                setting_text(r).c_str(), r.steps, fmt("%.3g", 1e3 * r.err_max).c_str(),
                fmt("%.3g", 1e3 * r.err_final).c_str(), fmt("%.2g", r.err_max / ref.nutation_pp).c_str(),
                fmt("%.2g", r.kept).c_str(), fmt("%.2g", r.phase).c_str(),
                fmt("%.3g", 1e3 * median(r.cpu)).c_str(), mj ? "-" : fmt("%.3g", 1e3 * median(r.cpu_to_T)).c_str(),
                mj ? fmt("%.3g", 1e3 * r.penetration).c_str() : std::to_string(r.switches).c_str());
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

// For each MuJoCo dt, the cheapest top_sim run at equal or better error among `only` (Peer::mujoco: any ladder).
void print_ratios(const std::vector<Rung>& rungs, Peer only) {
  std::printf("\n**Cheapest %s at equal or better error**\n\n| MuJoCo dt | its max error [mm] | its CPU [ms] | "
              "its nutation kept | cheapest top_sim at <= that error | its max error [mm] | its CPU [ms] to 5 s, no "
              "samples (with samples) | ratio, no samples: median (min-max) over repetitions | ratio, with samples | "
              "its nutation kept |\n|---|---|---|---|---|---|---|---|---|---|\n",
              only == Peer::mujoco ? "top_sim run, any ladder," : "top_sim dopri5 run");
  for (const Rung& m : rungs) {
    if (m.peer != Peer::mujoco) continue;
    const Rung* t = std::isfinite(m.err_max) ? cheapest_at(rungs, m.err_max, only) : nullptr;
    if (!t) {
      std::printf("| %g | %s | %s | %s | none | | | | | |\n", m.setting, fmt("%.3g", 1e3 * m.err_max).c_str(),
                  fmt("%.3g", 1e3 * median(m.cpu)).c_str(), fmt("%.2g", m.kept).c_str());
      continue;
    }
    std::printf("| %g | %.3g | %.3g | %.2g | %s %s | %.3g | %.3g (%.3g) | **%s** | %s | %.2g |\n", m.setting,
                1e3 * m.err_max, 1e3 * median(m.cpu), m.kept, method_name(t->peer),
                setting_text(*t).c_str(), 1e3 * t->err_max, 1e3 * median(t->cpu_to_T), 1e3 * median(t->cpu),
                ratio_text(m.cpu, t->cpu_to_T).c_str(), ratio_text(m.cpu, t->cpu).c_str(), t->kept);
  }
}

// The implicit midpoint rule's nutation frequency over the true one: arg R(i h w) / (h w) = 2 atan(h w / 2) / (h w).
double midpoint_frequency(double dt, double w) { return 2.0 * std::atan(0.5 * dt * w) / (dt * w); }

// The cheapest top_sim rung at <= err with the nutation kept in [0.9, 1.1] and, if asked, in phase.
const Rung* cheapest_keeping(const std::vector<Rung>& rungs, double err, bool in_phase) {
  const Rung* best = nullptr;
  for (const Rung& r : rungs)
    if (r.peer != Peer::mujoco && r.err_max <= err && r.kept >= 0.9 && r.kept <= 1.1 &&
        (!in_phase || r.phase <= kInPhase) &&
        (!best || median(r.cpu_to_T) < median(best->cpu_to_T)))
      best = &r;
  return best;
}

// Issue 21 item 5's target: the cheapest top_sim run, any ladder, at MuJoCo dt 1e-3's error or better with the
// nutation kept (0.9 to 1.1 of the reference's), and its CPU ratio to that MuJoCo run; then the same with the
// nutation also in phase (implicit_midpoint keeps its amplitude at any h, its frequency only at small h w).
void print_target(const std::vector<Rung>& rungs, double w) {
  const auto mj = std::find_if(rungs.begin(), rungs.end(),
                               [](const Rung& r) { return r.peer == Peer::mujoco && r.setting == 1e-3; });
  if (mj == rungs.end() || !std::isfinite(mj->err_max)) return;
  for (bool in_phase : {false, true}) {
    const Rung* best = cheapest_keeping(rungs, mj->err_max, in_phase);
    std::printf("\n**Target%s** (MuJoCo RK4 dt 1e-3: %.3g mm, %.3g ms; top_sim at <= that error with nutation kept in "
                "[0.9, 1.1]%s): ", in_phase ? ", nutation in phase" : "", 1e3 * mj->err_max, 1e3 * median(mj->cpu),
                in_phase ? " and its phase error <= 0.25" : "");
    if (!best) {
      std::printf("none\n");
      continue;
    }
    std::printf("%s %s, %.3g mm, nutation kept %.3g, phase error %.2g", method_name(best->peer),
                setting_text(*best).c_str(), 1e3 * best->err_max, best->kept, best->phase);
    if (best->peer == Peer::midpoint)
      std::printf(" at %.2g of its frequency (2 atan(h w / 2) / (h w))", midpoint_frequency(best->setting, w));
    std::printf(", %.3g ms to 5 s without samples: ratio **%s** (with samples %s)\n", 1e3 * median(best->cpu_to_T),
                ratio_text(mj->cpu, best->cpu_to_T).c_str(), ratio_text(mj->cpu, best->cpu).c_str());
  }
}

void write_csv(const std::string& file, const std::vector<Rung>& rungs) {
  std::ofstream csv(file);
  csv << "peer,setting,steps,mode_switches,err_max_m,err_final_m,penetration_m,nutation_kept,phase_error,repetition,"
         "cpu_s,cpu_to_T_s\n";
  for (const Rung& r : rungs)
    for (std::size_t i = 0; i < r.cpu.size(); ++i)
      csv << csv_name(r.peer) << "," << r.setting << "," << r.steps << "," << r.switches << "," << r.err_max << ","
          << r.err_final << "," << r.penetration << "," << r.kept << "," << r.phase << "," << i << "," << r.cpu[i] << ","
          << (r.peer == Peer::mujoco ? NAN : r.cpu_to_T[i]) << "\n";
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

// |R(i y)| of classical RK4: R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24.
double rk4_gain(double y) { return std::abs(std::complex<double>(1.0 - y * y / 2 + y * y * y * y / 24, y - y * y * y / 6)); }


// The nutation an rk4 run keeps against its stability function: the nutation is a linear mode of frequency w, each
// step multiplies it by |R(i h w)|, and the last second's peak-to-peak is set by its amplitude at its start. 10 %:
// |R|^(t/h) depends on w as (h w)^6, so 1 % in w is 6 % in the log of the prediction (about 6 % at dt 2e-3).
bool check_rk4_decay(const Scene& scene, double w, double ref_pp) {
  bool ok = true;
  for (double dt : {1e-3, 2e-3}) {
    const Track tr = track(configured(scene, Peer::rk4, dt), grid(dt, kT), false);
    const double kept = last_second_peak_to_peak(tr.t, tr.tilt) / ref_pp;
    const double predicted = std::pow(rk4_gain(dt * w), kKeptFrom / dt);
    ok &= expect(std::abs(kept / predicted - 1.0) < 0.1,
                 "rk4 dt " + fmt("%g", dt) + " keeps " + fmt("%.4f", kept) + " of the nutation; |R4(i h w)|^(" +
                     fmt("%g", kKeptFrom) + " s / h) = " + fmt("%.4f", predicted) + " (within 10 %)");
  }
  const Track coarse = track(configured(scene, Peer::rk4, 8e-3), grid(8e-3, kT), false);
  const double kept = last_second_peak_to_peak(coarse.t, coarse.tilt) / ref_pp;
  ok &= expect(kept < 0.01, "rk4 dt 8e-3 keeps " + fmt("%.2g", kept) + " of the nutation (< 0.01; |R4|^(4 s / h) = " +
                                fmt("%.2g", std::pow(rk4_gain(8e-3 * w), kKeptFrom / 8e-3)) + ")");
  return ok;
}

// implicit_midpoint at dt 5 ms (h w = 1.6): |R(iy)| = 1 keeps the nutation, and the slow motion is accurate.
bool check_midpoint(const Scene& scene, double ref_pp) {
  const double dt = 5e-3;
  const Track tr = track(configured(scene, Peer::midpoint, dt), grid(dt, kT));
  const double kept = last_second_peak_to_peak(tr.t, tr.tilt) / ref_pp;
  const double err = max_distance(tr.contact, track(with_rtol(scene, 1e-12), tr.t).contact);
  bool ok = expect(std::abs(kept - 1.0) < 0.05, "implicit_midpoint dt 5e-3 keeps " + fmt("%.4f", kept) +
                                                    " of the nutation (1 within 5 %)");
  ok &= expect(err < 8e-5, "implicit_midpoint dt 5e-3: max contact-point error " + fmt("%.3g", 1e3 * err) +
                               " mm at its step ends (< 0.08 mm)");
  return ok;
}

// fitted_midpoint at dt 3 pi / w (1.5 nutation periods): the nutation kept and in phase, the slow motion accurate;
// implicit_midpoint at that dt keeps the amplitude out of phase.
bool check_fitted(const Scene& scene, double w, double ref_pp) {
  const double dt = 3.0 * M_PI / w;
  const Track tr = track(configured(scene, Peer::fitted, dt), grid(dt, kT));
  const double kept = last_second_peak_to_peak(tr.t, tr.tilt) / ref_pp, phase = phase_error(scene, tr.t, tr.tilt, ref_pp);
  const double err = max_distance(tr.contact, track(with_rtol(scene, 1e-12), tr.t).contact);
  bool ok = expect(std::abs(kept - 1.0) < 0.1 && phase <= kInPhase,
                   "fitted_midpoint dt 3 pi / w = " + fmt("%.4g", dt) + " s keeps " + fmt("%.3f", kept) +
                       " of the nutation (1 within 10 %), phase error " + fmt("%.2f", phase) + " (<= 0.25: in phase)");
  ok &= expect(err < 8e-5, "fitted_midpoint dt 3 pi / w: max contact-point error " + fmt("%.3g", 1e3 * err) +
                               " mm at its step ends (< 0.08 mm)");
  const Track plain = track(configured(scene, Peer::midpoint, dt), grid(dt, kT), false);
  const double plain_phase = phase_error(scene, plain.t, plain.tilt, ref_pp);
  ok &= expect(plain_phase > 2 * kInPhase, "implicit_midpoint at that dt: phase error " + fmt("%.2f", plain_phase) +
                                           " (> 0.5: out of phase)");
  return ok;
}

// The nutation's frequency against the fast-top formula, rk4's damping against its stability function, dopri5 at a
// tight rtol keeping the nutation.
bool check_nutation(const Scene& scene) {
  const Track fine = track(with_rtol(scene, 1e-12), grid(kTiltInterval, kT), false);
  const double w = tilt_frequency(fine.t, fine.tilt), ref_pp = last_second_peak_to_peak(fine.t, fine.tilt);
  const double w_fast = top_sim::fast_top_nutation_frequency(scene.model, top_sim::initial_state(scene));
  bool ok = expect(std::abs(w / w_fast - 1.0) < 0.02, "the reference's nutation: w = " + fmt("%.1f", w) +
                                                        " rad/s; fast-top formula " + fmt("%.1f", w_fast) +
                                                        " rad/s (within 2 %: the formula leaves out the precession)");
  ok &= check_rk4_decay(scene, w, ref_pp);
  const Track last = dopri5_last_second(with_rtol(scene, 1e-8));
  const double kept = last_second_peak_to_peak(last.t, last.tilt) / ref_pp;
  ok &= expect(std::abs(kept - 1.0) < 0.03, "dopri5 rtol 1e-8 keeps " + fmt("%.4f", kept) + " of it (1 within 3 %)");
  ok &= check_midpoint(scene, ref_pp);
  ok &= check_fitted(scene, w_fast, ref_pp);
  return ok;
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
  ok &= check_nutation(scene);
  return ok ? 0 : 1;
}

// Where MuJoCo's error, and its loss of the nutation, come from: the step (same contact time constant, smaller dt) or
// the soft contact (same dt, softer contact). Untimed.
int softness(const Scene& scene) {
  const Path ref = top_sim_path(with_rtol(scene, 1e-12));
  const Track fine = track(with_rtol(scene, 1e-12), grid(kTiltInterval, kT, kKeptFrom), false);
  const double ref_pp = last_second_peak_to_peak(fine.t, fine.tilt);
  peer::MujocoTop mj(scene);
  std::printf("| MuJoCo dt | solref time constant | max error [mm] | max penetration [mm] | nutation kept |\n"
              "|---|---|---|---|---|\n");
  for (double dt : {1e-4, 2e-4, 5e-4, 1e-3})
    for (double tc : {2e-4, 5e-4, 1e-3, 2e-3, 5e-3}) {
      if (tc < 2.0 * dt) continue;
      mj.set_timestep(dt, tc);
      const double e = max_distance(mj.run(kT, kInterval), ref), pen = mj.max_penetration();
      const double kept = last_second_peak_to_peak(grid(dt, kT, kKeptFrom), mj.tilt_run(kT, kKeptFrom)) / ref_pp;
      std::printf("| %g | %g | %.3g | %.3g | %.2g |\n", dt, tc, 1e3 * e, 1e3 * pen, kept);
    }
  return 0;
}

const char* kUsage = "usage: peer_mujoco [--config DIR] [--reps N] [--csv FILE] [--mjcf] [--check] [--softness] [--pivot] "
                     "[--tippe-top] [--euler-disk]";

struct Options {
  std::string config = TOP_SIM_PEER_CONFIG_DIR, csv;
  int reps = 5;
  bool check = false, print_mjcf = false, softness = false, pivot = false, tippe_top = false, euler_disk = false;
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
    else if (a == "--pivot") o.pivot = true;
    else if (a == "--tippe-top") o.tippe_top = true;
    else if (a == "--euler-disk") o.euler_disk = true;
    else throw std::invalid_argument(kUsage);
  }
  return o;
}

int bench(const Scene& scene, const Options& opt) {
  const Reference ref = reference(scene);
  std::printf("MuJoCo %s; reference: top_sim dopri5 rtol 1e-12; its max distance from rtol 1e-11: %.2g m, from "
              "rtol 5e-13: %.2g m; nutation in the contact point f (theta_max - theta_min) = %.3g mm; its angular "
              "frequency (tilt period) w = %.1f rad/s; tilt peak-to-peak over the last second %.3g rad (nutation "
              "kept = a run's peak-to-peak there / this)\n\n",
              mj_versionString(), ref.self_error_1e11, ref.self_error_half, 1e3 * ref.nutation_pp, ref.nutation_w,
              ref.tilt_pp_last);
  peer::MujocoTop mj(scene);
  std::vector<Rung> rungs = ladder(scene);
  for (Rung& r : rungs) error_of(r, scene, mj, ref);
  time_interleaved(rungs, scene, mj, opt.reps);
  print_rungs(rungs, ref);
  print_ratios(rungs, Peer::mujoco);
  print_ratios(rungs, Peer::dopri5);
  print_target(rungs, ref.nutation_w);
  if (!opt.csv.empty()) write_csv(opt.csv, rungs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options opt = parse(argc, argv);
    if (opt.pivot) return peer::pivot(opt.config, opt.reps, opt.csv);
    const peer::ShapesOptions shapes{opt.reps, opt.check, opt.print_mjcf, opt.csv};
    if (opt.tippe_top) return peer::tippe_top(shapes);
    if (opt.euler_disk) return peer::euler_disk(shapes);
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
