// peer_mujoco --pivot (issue 32 part 8): an upright top spinning in place on a level plane, its patch pivoting, in
// top_sim (contact.patch_radius a, Coulomb mu, Hertzian pressure: lever Rbar = 3 pi a / 16) and in MuJoCo (condim 4,
// torsional friction coefficient mu Rbar: MuJoCo bounds the torsional torque by that length times the normal force).
// Closed form (physics.md section 12): the spin falls at the constant rate mu m g Rbar / I_f. Per run: the spin
// after kPivotT against the closed form, and the CPU time per simulated second (median of reps).
#include "pivot.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mujoco_top.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/state.hpp"

namespace peer {

namespace {

constexpr double kPivotT = 1.0;      // simulated time [s]
constexpr double kSpin0 = 100.0;     // start spin [rad/s]: above the aluminium top's upright threshold (34 rad/s)
constexpr double kMu = 0.25;         // Coulomb coefficient, PMMA's mu_c
constexpr double kPatch = 1.0e-3;    // patch radius a [m]: large enough for a spin loss of 7 % in kPivotT
constexpr double kMinTimed = 0.05;   // CPU seconds per timed sample: short runs are repeated until this

// CPU seconds of one call of `run`, median over reps of batches long enough for the clock.
template <class F>
double cpu_per_run(F run, int reps) {
  std::vector<double> samples;
  for (int r = 0; r < reps; ++r) {
    long n = 0;
    const double t0 = thread_cpu();
    double t1 = t0;
    while (t1 - t0 < kMinTimed) {
      run();
      ++n;
      t1 = thread_cpu();
    }
    samples.push_back((t1 - t0) / static_cast<double>(n));
  }
  return median(samples);
}

top_sim::Scene pivot_scene(const std::string& config_dir) {
  const std::string yaml =
      "description: upright aluminium top pivoting on a level plane (peer_mujoco --pivot)\n"
      "top: aluminium\n"
      "plane: {inclination: 0.0}\n"
      "friction: {law: coulomb, mu: " + num(kMu) + "}\n"
      "contact: {patch_radius: " + num(kPatch) + "}\n"
      "initial: {start: tilted, tilt: 0.0, spin: " + num(kSpin0) + "}\n"
      "duration: " + num(kPivotT) + "\n";
  return top_sim::parse_scene_text(yaml, "pivot", config_dir);
}

double top_sim_spin(const top_sim::Scene& s, long* steps = nullptr) {
  top_sim::Simulator sim(s);
  sim.advance_to(kPivotT);
  if (sim.fault() != top_sim::ContactFault::none) throw std::runtime_error("top_sim: " + sim.fault_message());
  if (steps) *steps = static_cast<long>(sim.stats().steps);
  const top_sim::StateVector& y = sim.state();
  return top_sim::angular_velocity(y).dot(top_sim::figure_axis(y));
}

// The same top as mujoco_top.cpp's mapping, on a level plane, with condim 4: friction = (mu, mu Rbar, 0) on both
// geoms (MuJoCo combines by the maximum, so both carry the same values).
std::string pivot_mjcf(const top_sim::Scene& s, double dt, const std::string& cone, double rbar) {
  const top_sim::Top& top = s.model.top;
  return "<mujoco model=\"top_sim_pivot\">\n"
         "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
         "  <option timestep=\"" + num(dt) + "\" integrator=\"RK4\" cone=\"" + cone + "\" gravity=\"0 0 " +
         num(-s.model.plane.gravity) + "\"/>\n"
         "  <default><geom condim=\"4\" friction=\"" + num(kMu) + " " + num(kMu * rbar) + " 0\" solref=\"" +
         num(2.0 * dt) + " 1\"/></default>\n"
         "  <worldbody>\n"
         "    <geom name=\"plane\" type=\"plane\" size=\"0 0 1\"/>\n"
         "    <body name=\"top\" pos=\"0 0 " + num(top.tip_radius + top.com_offset) + "\">\n"
         "      <joint name=\"free\" type=\"free\"/>\n"
         "      <inertial pos=\"0 0 0\" mass=\"" + num(top.mass) + "\" diaginertia=\"" + num(top.inertia_transverse) +
         " " + num(top.inertia_transverse) + " " + num(top.inertia_axial) + "\"/>\n"
         "      <geom name=\"tip\" type=\"sphere\" size=\"" + num(top.tip_radius) + "\" pos=\"0 0 " +
         num(-top.com_offset) + "\"/>\n"
         "    </body>\n"
         "  </worldbody>\n"
         "</mujoco>\n";
}

struct MjRun {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit MjRun(const std::string& xml) : m(compile(xml)), d(mj_makeData(m)) {}
  ~MjRun() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  // Spin (body-frame omega about the figure axis: the free joint's qvel[5]) after kPivotT from the upright start;
  // `half` gets it at kPivotT / 2 (the late half's rate is free of the start's normal-force transient).
  double spin(double* half = nullptr) {
    mj_resetData(m, d);
    d->qvel[5] = kSpin0;
    const long steps = std::lround(kPivotT / m->opt.timestep);
    for (long k = 0; k < steps; ++k) {
      mj_step(m, d);
      if (half && k + 1 == steps / 2) *half = d->qvel[5];
    }
    return d->qvel[5];
  }
};

struct Row {
  std::string engine, setting;
  double spin, error, cpu_per_s;
  long steps;
  double late_rate;  // spin lost per second over [kPivotT / 2, kPivotT]
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

int pivot(const std::string& config_dir, int reps, const std::string& csv) {
  const top_sim::Scene base = pivot_scene(config_dir);
  const top_sim::Top& top = base.model.top;
  const double rbar = 3.0 * M_PI * kPatch / 16.0;  // Hertzian pressure's lever (physics.md section 12)
  const double rate = kMu * top.mass * base.model.plane.gravity * rbar / top.inertia_axial;
  const double exact = kSpin0 - rate * kPivotT;
  std::printf("Pivoting top (aluminium: m %g kg, I_f %g kg m^2), upright on a level plane, spin %g rad/s, Coulomb mu "
              "%g, patch a = %g m, Rbar = 3 pi a / 16 = %.6g m (MuJoCo torsional coefficient mu Rbar = %.6g m); "
              "closed form: spin falls at mu m g Rbar / I_f = %.6g rad/s^2, %.10g rad/s at t = %g s; MuJoCo %s\n\n",
              top.mass, top.inertia_axial, kSpin0, kMu, kPatch, rbar, kMu * rbar, rate, exact, kPivotT,
              mj_versionString());
  std::vector<Row> rows;
  for (double rtol : {1e-3, 1e-6, 1e-9}) {
    top_sim::Scene s = base;
    s.integrator.method = top_sim::Method::dopri5;
    s.integrator.rtol = rtol;
    s.integrator.atol = 1e-2 * rtol;  // the convention of peer_mujoco's ladders
    long steps = 0;
    const double w = top_sim_spin(s, &steps);
    top_sim::Scene h = s;  // the same run stopped half-way, for the late half's rate
    top_sim::Simulator sim(h);
    sim.advance_to(0.5 * kPivotT);
    const double w_half = top_sim::angular_velocity(sim.state()).dot(top_sim::figure_axis(sim.state()));
    const double cpu = cpu_per_run([&] { top_sim_spin(s); }, reps);
    rows.push_back({"top_sim dopri5", fmt("rtol %g", rtol), w, w - exact, cpu / kPivotT, steps,
                    (w_half - w) / (0.5 * kPivotT)});
  }
  for (const char* cone : {"pyramidal", "elliptic"})
    for (double dt : {1e-4, 2e-4, 5e-4, 1e-3, 2e-3}) {
      MjRun run(pivot_mjcf(base, dt, cone, rbar));
      double w_half = 0.0;
      const double w = run.spin(&w_half);
      const double cpu = cpu_per_run([&] { run.spin(); }, reps);
      char setting[64];
      std::snprintf(setting, sizeof setting, "%s cone, RK4 dt %g", cone, dt);
      rows.push_back({"MuJoCo condim 4", setting, w, w - exact, cpu / kPivotT, std::lround(kPivotT / dt),
                      (w_half - w) / (0.5 * kPivotT)});
    }
  std::printf("| engine | setting | spin at %g s [rad/s] | minus closed form [rad/s] | error / spin lost | CPU per "
              "simulated s [ms] | steps | late-half rate / closed-form rate - 1 |\n|---|---|---|---|---|---|---|---|\n", kPivotT);
  for (const Row& r : rows)
    std::printf("| %s | %s | %.9f | %.3g | %.2g | %.3g | %ld | %.2g |\n", r.engine.c_str(), r.setting.c_str(), r.spin,
                r.error, r.error / (rate * kPivotT), 1e3 * r.cpu_per_s, r.steps, r.late_rate / rate - 1.0);
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "engine,setting,spin,closed_form,error,cpu_per_sim_second,steps,late_half_rate\n";
    for (const Row& r : rows)
      // the setting holds a comma: quoted
      out << r.engine << ",\"" << r.setting << "\"," << num(r.spin) << ',' << num(exact) << ',' << num(r.error) << ','
          << num(r.cpu_per_s) << ',' << r.steps << ',' << num(r.late_rate) << '\n';
  }
  return 0;
}

}  // namespace peer
