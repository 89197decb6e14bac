// peer_mujoco --euler-disk: Euler's disk in MuJoCo, a cylinder (radius a, thickness h, mass m) on a level plane,
// condim 6 (sliding, torsional and rolling friction), RK4, started in the steady rolling with its centre at rest.
//
// Steady rolling (docs/performance/mujoco_shapes.md derives it): disc normal n at angle beta from the vertical z,
// d the unit vector in the disc's plane pointing most downwards, c = h / 2; the contact is the lower face's rim
// point, r = a d - c n from the centre. Centre at rest and no slip: omega x r = 0, omega = -k r; beta constant and
// n precessing at Omega about z give k = Omega sin(beta) / a. Euler's equations about the centre (the normal force
// m g at the contact is the only torque; no friction force, the centre does not accelerate) give
//   Omega^2 sin(beta) / a = g (a cos(beta) - c sin(beta)) / (I1 a cos(beta) - I3 c sin(beta)),
// I1 = a^2 / 4 + h^2 / 12, I3 = a^2 / 2 per unit mass; a thin disc (c = 0): Omega^2 a sin(beta) = 4 g.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "mujoco_shapes.hpp"
#include "mujoco_top.hpp"

namespace peer {

namespace {

struct Disk {
  double a, h, m;  // radius, thickness [m], mass [kg]
};
// Radius: the commercial disc's 75 mm diameter (Davenport Collection's catalogue of the Tangent Toy disk); thickness
// and mass: no reliable published figure found, the brief's assumed 1/2 inch and 1 lb (a steel disc of that size:
// 0.44 kg).
constexpr Disk kCommercial{0.0375, 0.0127, 0.454};
constexpr Disk kThin{0.0375, 0.0375 / 100, 0.454};  // for the thin-disc relation

struct Friction {
  const char* name;
  double slide, torsion, roll;  // MuJoCo's friction triple: -, m, m
};
const Friction kDefaults{"MuJoCo's defaults", 1.0, 0.005, 1e-4};
const Friction kLow{"low", 0.3, 1e-5, 1e-6};

constexpr double kG = 9.81;
constexpr double kBeta0 = 0.5;         // start angle from the plane [rad]
constexpr double kSteadyT = 1.0;       // (a): steady rolling held over [s]
constexpr double kRestCap = 100.0;     // (b): the run stops here if not at rest [s]
constexpr double kRestKinetic = 1e-6;  // rest: kinetic energy below this fraction of its start
constexpr double kFitHigh = 0.45;      // (c): the fit's window ends here [rad] (after the start's transient)
constexpr double kSample = 1e-3;       // sample spacing of beta and the contact's azimuth [s]
// The ctest's steady rolling: low friction, the stiffest contact MuJoCo allows (solref 2 dt), over kCheckT; beta
// within kCheckBeta of beta0 (4 %), the mean circling rate within kCheckOmega of Omega (MuJoCo's soft contact
// costs a few per cent of it: docs/performance/mujoco_shapes.md).
constexpr double kCheckDt = 1e-4, kCheckT = 0.2, kCheckBeta = 0.02, kCheckOmega = 0.05;

// tc: the contact's solref time constant (MuJoCo's default 0.02 s; 2 dt is the stiffest MuJoCo allows).
std::string disk_mjcf(const Disk& k, const Friction& f, double dt, double tc = 0.02) {
  return "<mujoco model=\"euler disk\">\n"
         "  <option timestep=\"" + num(dt) + "\" integrator=\"RK4\" gravity=\"0 0 " + num(-kG) + "\"/>\n"
         "  <default><geom condim=\"6\" friction=\"" + num(f.slide) + " " + num(f.torsion) + " " + num(f.roll) +
         "\" solref=\"" + num(tc) + " 1\"/></default>\n"
         "  <worldbody>\n"
         "    <geom name=\"floor\" type=\"plane\" size=\"0 0 1\"/>\n"
         "    <body name=\"disk\">\n"
         "      <freejoint/>\n"
         "      <geom name=\"disk\" type=\"cylinder\" size=\"" + num(k.a) + " " + num(0.5 * k.h) + "\" mass=\"" +
         num(k.m) + "\"/>\n"
         "    </body>\n"
         "  </worldbody>\n"
         "</mujoco>\n";
}

struct Rolling {
  double Omega;            // the contact's circling rate [rad/s]
  Eigen::Quaterniond q;    // body z = the disc's normal n
  Eigen::Vector3d com, omega, r;  // centre [m], angular velocity [rad/s], centre to contact [m], world
};

Rolling steady_rolling(const Disk& k, double beta) {
  const double c = 0.5 * k.h, I1 = k.a * k.a / 4 + k.h * k.h / 12, I3 = k.a * k.a / 2;
  Rolling s;
  s.Omega = std::sqrt(kG * k.a * (k.a * std::cos(beta) - c * std::sin(beta)) /
                      (std::sin(beta) * (I1 * k.a * std::cos(beta) - I3 * c * std::sin(beta))));
  s.q = Eigen::Quaterniond(Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), n = s.q * z;
  const Eigen::Vector3d d = -(z - std::cos(beta) * n) / std::sin(beta);
  s.r = k.a * d - c * n;
  s.com = Eigen::Vector3d(0, 0, -s.r.z());
  s.omega = -(s.Omega * std::sin(beta) / k.a) * s.r;
  return s;
}

void set_state(MjInstance& mj, const Rolling& s, double depth) {
  mj_resetData(mj.m, mj.d);
  const Eigen::Vector3d w_body = s.q.conjugate() * s.omega;
  for (int i = 0; i < 3; ++i) {
    mj.d->qpos[i] = s.com[i];
    mj.d->qvel[i] = 0.0;
    mj.d->qvel[3 + i] = w_body[i];
  }
  mj.d->qpos[2] -= depth;
  mj.d->qpos[3] = s.q.w();
  mj.d->qpos[4] = s.q.x();
  mj.d->qpos[5] = s.q.y();
  mj.d->qpos[6] = s.q.z();
}

// How far MuJoCo's soft contact sinks under m g on one contact point: the disc standing upright at rest on its rim,
// the depth at which its centre's vertical acceleration vanishes (bisection; the force grows with the depth). The
// rolling start is lowered by it: a start at depth 0 has no normal force and drops.
double carrying_depth(MjInstance& mj, const Disk& k) {
  Rolling upright{0.0, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())),
                  Eigen::Vector3d(0, 0, k.a), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, -k.a)};
  double lo = 0.0, hi = 1e-2;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    set_state(mj, upright, mid);
    mj_forward(mj.m, mj.d);
    (mj.d->qacc[2] < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The disc's angle from the plane, the contact's azimuth (the normal's horizontal direction), energies.
double disc_beta(const mjData* d) { return tilt_from_vertical(d); }
double contact_azimuth(const mjData* d) {
  const Eigen::Vector3d n = body_axis(d);
  return std::atan2(n.y(), n.x());
}
double kinetic_energy(const mjModel* m, const mjData* d) {
  const Eigen::Vector3d v(d->qvel), w(d->qvel + 3), I(m->body_inertia + 3);  // body 1; cylinder: iquat identity
  return 0.5 * m->body_mass[1] * v.squaredNorm() + 0.5 * w.dot(I.asDiagonal() * w);
}

struct DiskRun {
  double dt = 0.0, depth = 0.0, Omega0 = 0.0, cpu = NAN;
  std::vector<double> t, beta, phi, speed;  // every kSample: [s], [rad], unwrapped [rad], centre speed [m/s]
  double t_rest = NAN, t_flat = NAN;  // kinetic energy below kRestKinetic of its start; beta below 1 degree [s]
  double energy0 = NAN, energy_end = NAN;  // kinetic + m g z of the centre [J]
};

DiskRun disk_run(MjInstance& mj, const Disk& k, double dt, double T, bool to_rest) {
  DiskRun r;
  r.dt = dt;
  mj.m->opt.timestep = dt;
  const Rolling s = steady_rolling(k, kBeta0);
  r.Omega0 = s.Omega;
  r.depth = carrying_depth(mj, k);
  set_state(mj, s, r.depth);
  const double ke0 = kinetic_energy(mj.m, mj.d);
  r.energy0 = ke0 + mj.m->body_mass[1] * kG * mj.d->qpos[2];
  const long steps = std::lround(T / dt), every = std::max(1L, std::lround(kSample / dt));
  double phi = contact_azimuth(mj.d);
  r.t = {0.0}, r.beta = {disc_beta(mj.d)}, r.phi = {phi}, r.speed = {0.0};
  const double c0 = thread_cpu();
  for (long i = 1; i <= steps; ++i) {
    mj_step(mj.m, mj.d);
    if (i % every != 0) continue;
    const double t = static_cast<double>(i) * dt, step = std::remainder(contact_azimuth(mj.d) - phi, 2 * M_PI);
    phi += step;
    r.t.push_back(t), r.beta.push_back(disc_beta(mj.d)), r.phi.push_back(phi);
    r.speed.push_back(Eigen::Vector3d(mj.d->qvel).norm());
    if (std::isnan(r.t_flat) && r.beta.back() < M_PI / 180) r.t_flat = t;
    if (std::isnan(r.t_rest) && kinetic_energy(mj.m, mj.d) < kRestKinetic * ke0) r.t_rest = t;
    if (to_rest && !std::isnan(r.t_rest) && !std::isnan(r.t_flat)) break;
  }
  r.cpu = (thread_cpu() - c0) / r.t.back();  // with the light probes above: every kSample, not every step
  r.energy_end = kinetic_energy(mj.m, mj.d) + mj.m->body_mass[1] * kG * mj.d->qpos[2];
  return r;
}

// The contact's mean circling rate between samples i and j [rad/s].
double circling(const DiskRun& r, std::size_t i, std::size_t j) { return (r.phi[j] - r.phi[i]) / (r.t[j] - r.t[i]); }

struct Steady {
  double beta_drift, beta_end, max_speed, Omega_ratio;  // [rad], [rad], [m/s], measured / predicted
};

Steady steady_summary(const DiskRun& r, double T) {
  std::size_t n = 0;
  Steady s{0.0, NAN, 0.0, NAN};
  for (; n < r.t.size() && r.t[n] <= T + 1e-12; ++n) {
    s.beta_drift = std::max(s.beta_drift, std::abs(r.beta[n] - kBeta0));
    s.max_speed = std::max(s.max_speed, r.speed[n]);
  }
  s.beta_end = r.beta[n - 1] - kBeta0;
  s.Omega_ratio = circling(r, 0, n - 1) / r.Omega0;
  return s;
}

// Fit of y = C (t0 - t)^p over the samples with beta in [lo, hi] before beta first falls below lo: t0 scanned
// after the window's end for the least squares of log y against log(t0 - t).
struct PowerFit {
  double p = NAN, t0 = NAN, p_Omega = NAN, rms = NAN;
  double p_onset = NAN, p_Omega_onset = NAN;  // the same with t0 the fall's onset (a singularity where it ends)
  std::size_t n = 0;
};

double slope(const std::vector<double>& x, const std::vector<double>& y, double* rms) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx), a0 = (sy - b * sx) / n;
  double ss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) ss += std::pow(y[i] - a0 - b * x[i], 2);
  if (rms) *rms = std::sqrt(ss / n);
  return b;
}

std::vector<double> log_to(const DiskRun& r, const std::vector<std::size_t>& idx, double t0) {
  std::vector<double> x;
  for (std::size_t i : idx) x.push_back(std::log(t0 - r.t[i]));
  return x;
}

// Where the disc starts to fall flat: the first sample whose beta falls by 10 % within the next 20 samples (20 ms;
// the rolling disc loses about 1 % in that time) [rad].
// Its sample index; the number of samples if it never does.
std::size_t collapse_index(const DiskRun& r) {
  for (std::size_t i = 0; i + 20 < r.beta.size(); ++i)
    if (r.beta[i + 20] < 0.9 * r.beta[i]) return i;
  return r.beta.size();
}

PowerFit late_fit(const DiskRun& r, double t_onset, double lo, double hi) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 10; i + 10 < r.t.size() && r.beta[i] >= lo; ++i)
    if (r.beta[i] <= hi) idx.push_back(i);
  PowerFit f;
  f.n = idx.size();
  if (idx.size() < 20) return f;
  std::vector<double> lb, lw;
  for (std::size_t i : idx) lb.push_back(std::log(r.beta[i])), lw.push_back(std::log(circling(r, i - 10, i + 10)));
  const double t_end = r.t[idx.back()], span = t_end - r.t[idx.front()];
  double best = INFINITY;
  for (double e = -6; e <= 0.5; e += 0.01) {  // t0 - t_end from 1e-6 to 3 spans, log-spaced
    const double t0 = t_end + span * std::pow(10.0, e);
    double rms = 0;
    const double p = slope(log_to(r, idx, t0), lb, &rms);
    if (rms < best) best = rms, f.p = p, f.t0 = t0, f.rms = rms;
  }
  f.p_Omega = slope(log_to(r, idx, f.t0), lw, nullptr);
  f.p_onset = slope(log_to(r, idx, t_onset), lb, nullptr);
  f.p_Omega_onset = slope(log_to(r, idx, t_onset), lw, nullptr);
  return f;
}

// ---- (a), (b), (c) --------------------------------------------------------------------------------------------

// (a) at each (dt, contact time constant).
void print_steady(const Friction& f, const std::vector<std::pair<double, double>>& settings) {
  std::printf("\n**(a) Steady rolling held over %g s** (beta0 %g rad, friction %s: %g, %g m, %g m):\n\n"
              "| disc | dt [s] | solref time constant [s] | Omega predicted [rad/s] | carrying depth [m] | max abs(beta - beta0) [rad] | beta(1 s) - "
              "beta0 [rad] | max centre speed [m/s] | mean circling rate / predicted |\n|---|---|---|---|---|---|---|---|---|\n",
              kSteadyT, kBeta0, f.name, f.slide, f.torsion, f.roll);
  for (const Disk* k : {&kCommercial, &kThin})
    for (const auto& [dt, tc] : settings) {
      MjInstance mj(disk_mjcf(*k, f, dt, tc));
      const DiskRun r = disk_run(mj, *k, dt, kSteadyT, false);
      const Steady s = steady_summary(r, kSteadyT);
      std::printf("| %s | %g | %g | %.4f | %.3g | %.3g | %+.3g | %.3g | %.5f |\n",
                  k == &kThin ? "thin (h = a/100)" : "commercial", dt, tc, r.Omega0, r.depth, s.beta_drift, s.beta_end,
                  s.max_speed, s.Omega_ratio);
    }
}

void write_disk_csv(const std::string& file, const std::vector<DiskRun>& runs, const std::vector<const char*>& names) {
  std::ofstream csv(file);
  csv << "friction,dt,t,beta,circling_rate\n";
  for (std::size_t k = 0; k < runs.size(); ++k)
    for (std::size_t i = 10; i + 10 < runs[k].t.size(); i += 10)
      csv << names[k] << "," << runs[k].dt << "," << runs[k].t[i] << "," << runs[k].beta[i] << ","
          << circling(runs[k], i - 10, i + 10) << "\n";
}

void print_rest(const std::vector<DiskRun>& runs, const std::vector<const char*>& names,
                const std::vector<std::vector<double>>& cpu) {
  std::printf("\n**(b) To rest from beta = %g rad** (rest: kinetic energy below %g of its start; flat: beta below 1 "
              "degree; cap %g s) and **(c) late-time exponents** (beta = C (t0 - t)^p over beta from 1.05 times the angle "
              "where the disc falls flat (beta falls by 10 %% within 20 ms) up to %g rad, t0 fitted; the circling rate's "
              "exponent q at that t0; p', q' with t0 the fall's onset instead; Moffatt: p = 1/3, q = -1/6):\n\n"
              "| friction | dt [s] | at rest [s] | flat [s] | falls flat from beta [rad] | beta at the end [rad] | energy at "
              "the end / start | centre speed at the end [m/s] | max circling rate [rad/s] | "
              "CPU per simulated s [s] (median, min-max) | p | q | t0 [s] | fit rms of log beta | p' | q' | samples |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n", kBeta0, kRestKinetic, kRestCap, kFitHigh);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const DiskRun& r = runs[k];
    double w_max = 0;
    for (std::size_t i = 10; i + 10 < r.t.size(); ++i) w_max = std::max(w_max, std::abs(circling(r, i - 10, i + 10)));
    const std::size_t onset = collapse_index(r);
    const double fall = onset < r.t.size() ? r.beta[onset] : NAN;
    const PowerFit f = onset < r.t.size() ? late_fit(r, r.t[onset], 1.05 * fall, kFitHigh) : PowerFit{};
    const auto [lo, hi] = std::minmax_element(cpu[k].begin(), cpu[k].end());
    std::printf("| %s | %g | %.3f | %.3f | %.4g | %.4g | %.3f | %.3g | %.4g | %.3g (%.3g-%.3g) | %.3f | %.3f | %.4f | %.2g "
                "| %.3f | %.3f | %zu |\n", names[k], r.dt, r.t_rest, r.t_flat, fall, r.beta.back(),
                r.energy_end / r.energy0, r.speed.back(), w_max, median(cpu[k]), *lo, *hi,
                f.p, f.p_Omega, f.t0, f.rms, f.p_onset, f.p_Omega_onset, f.n);
  }
}

}  // namespace

namespace {

// (b) and (c): each friction at each dt, to rest, timed reps times (interleaved); the first repetition's samples.
void rest_runs(int reps, const std::string& csv) {
  const std::vector<std::pair<const Friction*, double>> cases = {
      {&kDefaults, 1e-3}, {&kDefaults, 1e-4}, {&kLow, 1e-3}, {&kLow, 1e-4}};
  std::vector<DiskRun> runs(cases.size());
  std::vector<std::vector<double>> cpu(cases.size());
  std::vector<const char*> names;
  for (const auto& c : cases) names.push_back(c.first == &kDefaults ? "defaults" : "low");
  for (int rep = 0; rep < reps; ++rep)
    for (std::size_t k = 0; k < cases.size(); ++k) {
      MjInstance mj(disk_mjcf(kCommercial, *cases[k].first, cases[k].second));
      DiskRun r = disk_run(mj, kCommercial, cases[k].second, kRestCap, true);
      cpu[k].push_back(r.cpu);
      if (rep == 0) runs[k] = std::move(r);
    }
  print_rest(runs, names, cpu);
  if (!csv.empty()) write_disk_csv(csv, runs, names);
}

// MuJoCo's own view of the start (mj_forward at the carrying depth): the contact point's velocity from MuJoCo's
// angular and linear velocity, and the angular acceleration against the steady precession's (omega-dot =
// Omega z x omega).
struct StartView {
  double contact_speed, centre_speed, angular_acc_error, centre_acc;  // [m/s], [m/s], relative, [m/s^2]
};

StartView start_view(const Disk& k, const Friction& f, double dt) {
  MjInstance mj(disk_mjcf(k, f, dt));
  const Rolling s = steady_rolling(k, kBeta0);
  set_state(mj, s, carrying_depth(mj, k));
  mj_forward(mj.m, mj.d);
  mjtNum v[6];
  mj_objectVelocity(mj.m, mj.d, mjOBJ_BODY, 1, v, 0);
  const Eigen::Vector3d w(v[0], v[1], v[2]), vc(v[3], v[4], v[5]);
  const Eigen::Vector3d expected = s.q.conjugate() * (s.Omega * Eigen::Vector3d::UnitZ().cross(s.omega));
  const Eigen::Vector3d acc(mj.d->qacc + 3);
  return {(vc + w.cross(s.r)).norm(), vc.norm(), (acc - expected).norm() / expected.norm(),
          Eigen::Vector3d(mj.d->qacc).norm()};
}

void print_start(const Friction& f) {
  std::printf("\n**MuJoCo's view of the start** (mj_forward, friction %s):\n\n| disc | contact point speed [m/s] | "
              "centre speed [m/s] | centre acceleration [m/s^2] | angular acceleration off the steady precession's "
              "(relative) |\n|---|---|---|---|---|\n", f.name);
  for (const Disk* k : {&kCommercial, &kThin}) {
    const StartView v = start_view(*k, f, 1e-4);
    std::printf("| %s | %.2g | %.2g | %.3g | %.3g |\n", k == &kThin ? "thin" : "commercial", v.contact_speed,
                v.centre_speed, v.centre_acc, v.angular_acc_error);
  }
}

int disk_check() {
  bool ok = true;
  const Rolling thin = steady_rolling(kThin, kBeta0), thick = steady_rolling(kCommercial, kBeta0);
  const Rolling flat = steady_rolling(Disk{kThin.a, 0.0, kThin.m}, kBeta0);
  const double exact = flat.Omega * flat.Omega * kThin.a * std::sin(kBeta0) / (4 * kG);
  ok &= expect(std::abs(exact - 1) < 1e-12, "h = 0: Omega^2 a sin(beta) / 4 g = " + fmt("%.15f", exact) +
                                                " (1 within 1e-12)");
  // First order in c / a: 1 + (c / a) tan(beta) (I3 / I1 - 1) = 1 + (c / a) tan(beta); the next term 2 (c/a)^2 tan^2.
  const double relation = thin.Omega * thin.Omega * kThin.a * std::sin(kBeta0) / (4 * kG);
  const double first = 1 + 0.5 * kThin.h / kThin.a * std::tan(kBeta0);
  ok &= expect(std::abs(relation - first) < 5e-5, "h = a/100: Omega^2 a sin(beta) / 4 g = " + fmt("%.6f", relation) +
                                                     "; first order in h / a: " + fmt("%.6f", first) + " (within 5e-5)");
  for (const Rolling* s : {&thin, &thick})
    ok &= expect(s->omega.cross(s->r).norm() < 1e-12 * s->omega.norm() * s->r.norm() && std::abs(s->com.z() + s->r.z()) < 1e-15,
                 "start: omega parallel to the centre-to-contact vector, the contact on the floor");
  for (const Disk* k : {&kCommercial, &kThin}) {
    MjInstance mj(disk_mjcf(*k, kLow, kCheckDt, 2 * kCheckDt));
    const double* I = mj.m->body_inertia + 3, *iq = mj.m->body_iquat + 4;
    const double I1 = k->m * (k->a * k->a / 4 + k->h * k->h / 12), I3 = k->m * k->a * k->a / 2;
    ok &= expect(iq[0] == 1 && std::abs(I[0] / I1 - 1) < 1e-12 && I[1] == I[0] && std::abs(I[2] / I3 - 1) < 1e-12,
                 "MuJoCo's cylinder has the derivation's I1 = m (a^2/4 + h^2/12), I3 = m a^2/2 on the body axes");
    const Steady s = steady_summary(disk_run(mj, *k, kCheckDt, kCheckT, false), kCheckT);
    ok &= expect(s.beta_drift < kCheckBeta && std::abs(s.Omega_ratio - 1) < kCheckOmega,
                 std::string(k == &kThin ? "thin" : "commercial") + ", dt " + fmt("%g", kCheckDt) + ", stiffest contact: " +
                     "over " + fmt("%g", kCheckT) + " s max abs(beta - beta0) " + fmt("%.3g", s.beta_drift) +
                     " rad (< " + fmt("%g", kCheckBeta) + "), circling rate " + fmt("%.4f", s.Omega_ratio) +
                     " of the steady rolling's (1 within " + fmt("%g", kCheckOmega) + ")");
  }
  for (const Disk* k : {&kCommercial, &kThin}) {
    const StartView v = start_view(*k, kLow, 1e-4);
    ok &= expect(v.contact_speed < 1e-12 && v.centre_speed < 1e-12,
                 std::string(k == &kThin ? "thin" : "commercial") + ": MuJoCo's contact point speed at the start " +
                     fmt("%.2g", v.contact_speed) + " m/s, centre " + fmt("%.2g", v.centre_speed) + " m/s (< 1e-12)");
  }
  return ok ? 0 : 1;
}

}  // namespace

int euler_disk(const ShapesOptions& o) {
  if (o.print_mjcf) {
    std::cout << disk_mjcf(kCommercial, kLow, 1e-4);
    return 0;
  }
  if (o.check) return disk_check();
  std::printf("MuJoCo %s, Euler's disk: a cylinder, radius %g m, thickness %g m, mass %g kg, condim 6, RK4, default "
              "solref/solimp\n", mj_versionString(), kCommercial.a, kCommercial.h, kCommercial.m);
  print_start(kLow);
  print_start(kDefaults);
  print_steady(kLow, {{1e-3, 0.02}, {1e-4, 0.02}, {1e-4, 2e-4}});
  print_steady(kDefaults, {{1e-3, 0.02}, {1e-4, 0.02}, {1e-4, 2e-4}});
  rest_runs(o.reps, o.csv);
  return 0;
}

}  // namespace peer
