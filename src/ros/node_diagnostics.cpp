#include "node_diagnostics.hpp"

#include <ctime>
#include <sstream>

namespace top_sim_ros {

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

NodeDiagnostics::NodeDiagnostics(double wall) : wall_(wall), cpu_(process_cpu_seconds()) {}

void NodeDiagnostics::add_physics(std::size_t steps, double cpu_seconds) {
  steps_ += steps;
  step_cpu_ += cpu_seconds;
}

namespace {

struct TopCounts {
  std::size_t behind = 0, faulted = 0, switches = 0;
};

TopCounts count(TopSet& tops) {
  TopCounts c;
  for (auto& t : tops) {
    if (t->pacer().behind()) ++c.behind;
    if (t->sim().fault() != top_sim::ContactFault::none) ++c.faulted;
    c.switches += t->mode_switches();
  }
  return c;
}

std::string behind_text(const top_sim::Pacer& p, const TopCounts& c, std::size_t tops) {
  std::ostringstream os;
  os.precision(3);
  if (p.behind()) os << "falling behind: achieved " << p.achieved_factor() << " of requested " << p.real_time_factor();
  if (c.behind > (p.behind() ? 1u : 0u))
    os << (p.behind() ? "; " : "") << c.behind << " of " << tops << " tops falling behind";
  return os.str();
}

}  // namespace

void NodeDiagnostics::fill(diagnostic_updater::DiagnosticStatusWrapper& st, TopSet& tops, const NodeStatus& node,
                           double wall) {
  using diagnostic_msgs::DiagnosticStatus;
  NodeTop& top = tops.launch_top();
  const top_sim::Simulator& sim = top.sim();
  const top_sim::Snapshot s = sim.snapshot();
  const TopCounts c = count(tops);
  const double cpu = process_cpu_seconds(), dw = wall - wall_;
  if (sim.fault() != top_sim::ContactFault::none)
    st.summary(DiagnosticStatus::ERROR, "contact fault: " + sim.fault_message());
  else if (c.faulted > 0)
    st.summary(DiagnosticStatus::ERROR, std::to_string(c.faulted) + " spawned tops stopped by a contact fault");
  else if (c.behind > 0)
    st.summary(DiagnosticStatus::WARN, behind_text(top.pacer(), c, tops.size()));
  else if (node.lcm.rfind("error", 0) == 0)
    st.summary(DiagnosticStatus::WARN, "LCM off: " + node.lcm);
  else if (sim.end_state() != top_sim::EndState::none)
    st.summary(DiagnosticStatus::OK, std::string("ended: ") + top_sim::to_string(sim.end_state()));
  else
    st.summary(DiagnosticStatus::OK, node.paused ? "paused" : "running");
  st.add("tops", tops.size());
  st.add("tops falling behind", c.behind);
  st.add("tops whose topics are not yet advertised", node.topics_pending);
  st.add("tops stopped by a contact fault", c.faulted);
  st.add("simulated time [s]", s.t);
  st.add("requested real-time factor", node.requested_factor);
  st.add("achieved real-time factor", top.pacer().achieved_factor());
  st.add("behind", top.pacer().behind());
  st.add("physics budget per tick [ms]", 1e3 * top.pacer().budget());
  st.add("debt drops (more than 0.5 s behind)", top.pacer().debt_drops());
  st.add("dropped simulated time [s]", top.pacer().dropped_sim_seconds());
  st.add("rejected commands", node.rejected);
  st.add("publish rate requested [Hz]", node.publish_rate);
  st.add("publish rate achieved [Hz]", dw > 0.0 ? (node.published - published_) / dw : 0.0);
  st.add("integrator steps (window)", steps_);
  st.add("cost per step [us]", steps_ > 0 ? 1e6 * step_cpu_ / steps_ : 0.0);
  st.add("node CPU share [fraction of one core]", dw > 0.0 ? (cpu - cpu_) / dw : 0.0);
  st.add("energy balance residual", s.energy_balance_residual);
  st.add("max energy balance residual", sim.max_energy_residual());
  st.add("regime", top_sim::to_string(s.regime));
  st.add("contact mode", top_sim::to_string(s.contact_mode));
  st.add("contact-mode switches", c.switches);
  st.add("gap [m]", s.gap);
  st.add("alpha [rad]", s.alpha);
  st.add("spin [rad/s]", s.spin);
  st.add("paused", node.paused);
  st.add("lcm", node.lcm);
  wall_ = wall;
  cpu_ = cpu;
  published_ = node.published;
  steps_ = 0;
  step_cpu_ = 0.0;
}

}  // namespace top_sim_ros
