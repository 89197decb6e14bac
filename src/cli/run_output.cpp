#include "run_output.hpp"

#include <cmath>
#include <ctime>
#include <iomanip>
#include <sstream>
#include <utility>

#include "top_sim/plane.hpp"
#include "top_sim/trajectory.hpp"

namespace top_sim {

namespace {


std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}
std::string vec(std::initializer_list<double> v) {
  std::string s = "[";
  for (double x : v) s += (s.size() > 1 ? ", " : "") + num(x);
  return s + "]";
}
std::string quoted(const std::string& text) {
  std::string s = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') s += '\\';
    if (c == '\n') { s += "\\n"; continue; }
    s += c;
  }
  return s + "\"";
}
}  // namespace

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

namespace {

// advance_to in slices of progress_interval wall seconds, reporting the time reached after each.
void advance(Simulator& sim, double t, const RunOptions& opt) {
  if (!opt.on_progress) {
    sim.advance_to(t);
    return;
  }
  while (!sim.advance_to(t, opt.progress_interval)) opt.on_progress(sim.time());
}

}  // namespace

RunResult run(Simulator& sim, const RunOptions& opt) {
  RunResult r;
  const double t0 = sim.time();
  const double t_end = t0 + opt.duration;
  const double t_mark = t0 + 0.8 * opt.duration;
  const double cpu0 = thread_cpu_seconds();
  std::optional<Eigen::Vector2d> mark;

  const std::array<double, kContactModeCount> seconds0 = sim.mode_seconds();
  const std::uint64_t switches0 = sim.mode_switch_count();
  sim.take_mode_switches();  // only this run's switches
  auto collect = [&]() {
    for (const ModeSwitch& m : sim.take_mode_switches())
      if (r.mode_switches.size() < Simulator::kMaxPendingSwitches) r.mode_switches.push_back(m);
  };
  auto advance_to = [&](double t) {  // every advance of the run keeps its mode switches
    advance(sim, t, opt);
    collect();
  };
  auto sample = [&](double t) {
    advance_to(t);
    if (opt.on_sample) opt.on_sample(sim.snapshot());
  };
  if (opt.sample_rate > 0.0 && opt.on_sample) {
    opt.on_sample(sim.snapshot());
    const double dt = 1.0 / opt.sample_rate;
    for (long k = 1;; ++k) {
      const double t = t0 + k * dt;
      if (t > t_end + 1e-9 * dt) break;
      if (!mark && t >= t_mark) {
        advance_to(t_mark);
        mark = position(sim.state());
      }
      sample(t);
      if (sim.fault() != ContactFault::none) break;
    }
  } else {
    advance_to(t_mark);
    mark = position(sim.state());
  }
  advance_to(t_end);
  r.cpu_seconds = thread_cpu_seconds() - cpu0;
  r.mode_switch_count = sim.mode_switch_count() - switches0;
  const std::array<double, kContactModeCount> seconds1 = sim.mode_seconds();
  for (int i = 0; i < kContactModeCount; ++i) r.mode_seconds[i] = seconds1[i] - seconds0[i];
  r.sim_seconds = sim.time() - t0;
  r.final = sim.snapshot();
  r.stats = sim.stats();
  r.max_energy_residual = sim.max_energy_residual();
  if (mark && sim.fault() == ContactFault::none) {
    const Eigen::Vector2d d = position(sim.state()) - *mark;
    if (d.norm() > 0.0) r.phi_measured = travel_angle(d.x(), d.y());
  }
  const StationaryState st = sim.stationary();
  if (st.exists && st.phi_defined)
    r.phi_star = st.phi;
  else
    r.stationary_note = st.reason;
  return r;
}

void write_csv_header(std::ostream& os) {
  const char* sep = "";
  for (const TrajectoryColumn& c : trajectory_columns()) os << std::exchange(sep, ",") << c.name;
  os << '\n';
}

void write_csv_row(std::ostream& os, const Snapshot& s) {
  os << std::setprecision(12);
  const char* sep = "";
  for (const TrajectoryColumn& c : trajectory_columns()) {
    os << std::exchange(sep, ",");
    if (c.text) os << c.text(s); else os << c.value(s);
  }
  os << '\n';
}

std::string summary_json(const Scene& scene, const RunResult& r) {
  const Snapshot& f = r.final;
  std::ostringstream os;
  os << "{\n"
     << "  \"scene\": " << quoted(scene.source) << ",\n"
     << "  \"method\": " << quoted(to_string(scene.integrator.method)) << ",\n"
     << "  \"model\": " << quoted(to_string(scene.model.kind)) << ",\n"
     << "  \"normal_force\": " << quoted(to_string(scene.model.normal_force)) << ",\n"
     << "  \"sim_seconds\": " << num(r.sim_seconds) << ",\n"
     << "  \"cpu_seconds\": " << num(r.cpu_seconds) << ",\n"
     << "  \"real_time_factor\": " << num(r.cpu_seconds > 0 ? r.sim_seconds / r.cpu_seconds : NAN) << ",\n"
     << "  \"steps\": " << r.stats.steps << ",\n"
     << "  \"rhs_evaluations\": " << r.stats.rhs_evaluations << ",\n"
     << "  \"regime\": " << quoted(to_string(f.regime)) << ",\n"
     << "  \"phi_measured\": " << (r.phi_measured ? num(*r.phi_measured) : "null") << ",\n"
     << "  \"phi_star\": " << (r.phi_star ? num(*r.phi_star) : "null") << ",\n"
     << "  \"stationary_note\": " << (r.stationary_note.empty() ? "null" : quoted(r.stationary_note)) << ",\n"
     << "  \"final\": {\n"
     << "    \"t\": " << num(f.t) << ",\n"
     << "    \"alpha\": " << num(f.alpha) << ",\n"
     << "    \"position\": " << vec({f.contact_point.x(), f.contact_point.y()}) << ",\n"
     << "    \"velocity\": " << vec({f.tip_velocity.x(), f.tip_velocity.y()}) << ",\n"
     << "    \"f_hat\": " << vec({f.figure_axis.x(), f.figure_axis.y(), f.figure_axis.z()}) << ",\n"
     << "    \"omega\": " << vec({f.angular_velocity.x(), f.angular_velocity.y(), f.angular_velocity.z()}) << ",\n"
     << "    \"spin\": " << num(f.spin) << ",\n"
     << "    \"rotor_spin\": " << (f.has_rotor ? num(f.rotor_spin) : "null") << ",\n"
     << "    \"slip\": " << num(f.slip) << ",\n"
     << "    \"phi\": " << num(f.phi) << "\n"
     << "  },\n"
     << "  \"energy_balance_residual\": " << num(r.max_energy_residual) << ",\n"
     << "  \"contact_fault\": " << (f.fault == ContactFault::none ? "null" : quoted(f.fault_message)) << ",\n"
     << "  \"contact_fault_kind\": " << (f.fault == ContactFault::none ? "null" : quoted(to_string(f.fault))) << ",\n"
     << "  \"contact_mode\": " << (f.fault == ContactFault::none ? quoted(to_string(f.contact_mode)) : "null") << ",\n"
     << "  \"mode_seconds\": {";
  for (int i = 0; i < kContactModeCount; ++i)
    os << (i ? ", " : "") << quoted(to_string(static_cast<ContactMode>(i))) << ": " << num(r.mode_seconds[i]);
  os << "},\n"
     << "  \"mode_switch_count\": " << r.mode_switch_count << ",\n"
     << "  \"mode_switches\": [";
  for (std::size_t i = 0; i < r.mode_switches.size(); ++i) {
    const ModeSwitch& m = r.mode_switches[i];
    os << (i ? ",\n    " : "\n    ") << "{\"t\": " << num(m.t) << ", \"kind\": " << quoted(to_string(m.kind))
       << ", \"from\": " << quoted(to_string(m.from)) << ", \"to\": " << quoted(to_string(m.to))
       << ", \"energy_change\": " << num(m.energy_change) << "}";
  }
  os << (r.mode_switches.empty() ? "]\n" : "\n  ]\n") << "}\n";
  return os.str();
}

}  // namespace top_sim
