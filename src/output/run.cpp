#include "run.hpp"

#include <algorithm>
#include <cmath>

#include "top_sim/plane.hpp"
#include "top_sim/trajectory.hpp"

namespace top_sim {

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

double mark_time(double t0, double t_end) { return t0 + 0.8 * (t_end - t0); }

std::optional<double> travel_since(const Eigen::Vector2d& mark, const Snapshot& last) {
  const Eigen::Vector2d d = last.contact_point.head<2>() - mark;
  if (faulted(last) || !(d.norm() > 0.0)) return std::nullopt;
  return travel_angle(d.x(), d.y());
}

void SummaryAccumulator::add(const Snapshot& s) {
  const Snapshot& prev = sum_.last;
  if (sum_.samples == 0) {
    sum_.t_first = s.t;
  } else {
    const double dt = s.t - prev.t;
    sum_.regime_seconds[code(prev.regime)] += dt;
    sum_.mode_seconds[code(prev.contact_mode)] += dt;
    if (s.contact_mode != prev.contact_mode) {
      ModeSwitch m;
      m.t = s.t;
      m.from = prev.contact_mode;
      m.to = s.contact_mode;
      if (sum_.mode_changes.size() < Simulator::kMaxPendingSwitches) sum_.mode_changes.push_back(m);
      ++sum_.mode_change_count;
    }
  }
  if (!mark_ && s.t >= t_mark_) {  // the contact point at t_mark, linear between the samples around it
    const bool between = sum_.samples > 0 && prev.t < t_mark_;
    const double w = between ? (t_mark_ - prev.t) / (s.t - prev.t) : 1.0;
    const Eigen::Vector2d from = between ? Eigen::Vector2d(prev.contact_point.head<2>()) : Eigen::Vector2d::Zero();
    mark_ = (1.0 - w) * from + w * s.contact_point.head<2>();
  }
  sum_.max_energy_residual = std::max(sum_.max_energy_residual, s.energy_balance_residual);
  sum_.t_last = s.t;
  sum_.last = s;
  ++sum_.samples;
}

SampledSummary SummaryAccumulator::result() const {
  SampledSummary r = sum_;
  if (mark_) r.phi_measured = travel_since(*mark_, sum_.last);
  return r;
}

void set_phi_star(const StationaryState& st, std::optional<double>& phi_star, std::string& note) {
  if (st.exists && st.phi_defined)
    phi_star = st.phi;
  else
    note = st.reason;
}

namespace {

// Per-name seconds of the run: the simulator's counts now less those at its start.
template <std::size_t N>
std::array<double, N> since(const std::array<double, N>& start, const std::array<double, N>& now) {
  std::array<double, N> d{};
  for (std::size_t i = 0; i < N; ++i) d[i] = now[i] - start[i];
  return d;
}

// The samples' summary, with the run's end when the last sample is before it (not passed to on_sample).
SampledSummary with_end(SummaryAccumulator& samples, const Simulator& sim) {
  if (sim.time() > samples.t_last()) samples.add(sim.snapshot());
  return samples.result();
}

}  // namespace

RunResult run(Simulator& sim, const RunOptions& opt) {
  RunResult r;
  const double t0 = sim.time(), t_end = t0 + opt.duration;
  const double t_mark = mark_time(t0, t_end);
  const double cpu0 = thread_cpu_seconds();
  std::optional<Eigen::Vector2d> mark;
  const std::array<double, kContactModeCount> seconds0 = sim.mode_seconds();
  const std::array<double, kRegimeCount> regime_seconds0 = sim.regime_seconds();
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
  SummaryAccumulator sampled(t_mark);
  auto take_sample = [&]() {
    const Snapshot s = sim.snapshot();
    sampled.add(s);
    if (opt.on_sample) opt.on_sample(s);
  };
  const bool sampling = opt.sample_rate > 0.0;
  if (sampling) {
    take_sample();
    const long n = last_sample_index(opt.duration, opt.sample_rate);
    for (long k = 1; k <= n; ++k) {
      const double t = sample_time(t0, k, opt.sample_rate);
      if (!mark && t >= t_mark) {
        advance_to(t_mark);
        mark = position(sim.state());
      }
      advance_to(t);
      take_sample();
      if (sim.stopped()) break;
    }
  } else {
    advance_to(t_mark);
    mark = position(sim.state());
  }
  advance_to(t_end);
  r.cpu_seconds = thread_cpu_seconds() - cpu0;
  if (sampling) r.sampled = with_end(sampled, sim);
  r.mode_switch_count = sim.mode_switch_count() - switches0;
  r.mode_seconds = since(seconds0, sim.mode_seconds());
  r.regime_seconds = since(regime_seconds0, sim.regime_seconds());
  r.handovers = sim.handovers();
  r.reduced_seconds = sim.reduced_seconds();
  r.sim_seconds = sim.time() - t0;
  r.final = sim.snapshot();
  r.stats = sim.stats();
  r.max_energy_residual = sim.max_energy_residual();
  if (mark) r.phi_measured = travel_since(*mark, r.final);
  set_phi_star(sim.stationary(), r.phi_star, r.stationary_note);
  return r;
}

}  // namespace top_sim
