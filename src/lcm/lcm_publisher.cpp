// LCM adapter over the core's Snapshot.
#include "lcm_publisher.hpp"

#include <cmath>
#include <lcm/lcm-cpp.hpp>

#include "top_sim/top_state_t.hpp"

namespace top_sim_lcm {

namespace {
void copy3(const Eigen::Vector3d& v, double* out) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}
}  // namespace

// The message's constants are the core's codes (lcm/top_state_t.lcm keeps their values).
using top_sim::top_state_t;
static_assert(top_state_t::NUTATING == top_sim::code(top_sim::Regime::nutating), "top_state_t regime code");
static_assert(top_state_t::PRECESSING == top_sim::code(top_sim::Regime::precessing), "top_state_t regime code");
static_assert(top_state_t::SLEEPING == top_sim::code(top_sim::Regime::sleeping), "top_state_t regime code");
static_assert(top_state_t::SLIDING == top_sim::code(top_sim::Regime::sliding), "top_state_t regime code");
static_assert(top_state_t::CONTACT_FAULT == top_sim::code(top_sim::Regime::contact_fault), "top_state_t regime code");
static_assert(top_state_t::UPRIGHT == top_sim::code(top_sim::Regime::upright), "top_state_t regime code");
static_assert(top_state_t::INVERTING == top_sim::code(top_sim::Regime::inverting), "top_state_t regime code");
static_assert(top_state_t::INVERTED == top_sim::code(top_sim::Regime::inverted), "top_state_t regime code");
static_assert(top_state_t::TUMBLING == top_sim::code(top_sim::Regime::tumbling), "top_state_t regime code");
static_assert(top_state_t::ROLLING_ON_SHAPES == top_sim::code(top_sim::Regime::rolling), "top_state_t regime code");
static_assert(top_state_t::ON_CROWN == top_sim::code(top_sim::Regime::on_crown), "top_state_t regime code");
static_assert(top_state_t::ON_STEM == top_sim::code(top_sim::Regime::on_stem), "top_state_t regime code");
static_assert(top_state_t::AT_REST == top_sim::code(top_sim::Regime::at_rest), "top_state_t regime code");
static_assert(top_state_t::LYING_FLAT == top_sim::code(top_sim::Regime::lying_flat), "top_state_t regime code");
static_assert(top_state_t::FALLEN == top_sim::code(top_sim::Regime::fallen), "top_state_t regime code");
static_assert(top_state_t::SLIPPING == top_sim::code(top_sim::ContactMode::slipping), "top_state_t mode code");
static_assert(top_state_t::ROLLING == top_sim::code(top_sim::ContactMode::rolling), "top_state_t mode code");
static_assert(top_state_t::FLIGHT == top_sim::code(top_sim::ContactMode::flight), "top_state_t mode code");

void to_lcm(const top_sim::Snapshot& s, const Pacing& pacing, top_sim::top_state_t& out) {
  out.utime = static_cast<int64_t>(std::llround(s.t * 1e6));
  out.alpha = s.alpha;
  copy3(s.com, out.position);
  out.orientation[0] = s.orientation.w();
  out.orientation[1] = s.orientation.x();
  out.orientation[2] = s.orientation.y();
  out.orientation[3] = s.orientation.z();
  copy3(s.com_velocity, out.velocity);
  copy3(s.angular_velocity, out.angular_velocity);
  copy3(s.tip_center, out.tip_center);
  copy3(s.tip_velocity, out.tip_velocity);
  copy3(s.contact_point, out.contact_point);
  copy3(s.figure_axis, out.figure_axis);
  out.spin = s.spin;
  out.has_rotor = s.has_rotor;
  out.rotor_spin = s.rotor_spin;
  out.slip = s.slip;
  out.mu = s.mu;
  out.friction_law = pacing.friction_law;
  out.normal_force = s.normal_force;
  copy3(s.friction_force, out.friction_force);
  out.drilling_torque = s.drilling_torque;
  out.patch_radius = s.patch_radius;
  out.phi = s.phi;
  out.has_stationary_state = s.has_stationary_state;
  out.phi_star = s.phi_star;
  out.regime = static_cast<int8_t>(top_sim::code(s.regime));
  out.regime_name = top_sim::to_string(s.regime);
  out.contact_mode = static_cast<int8_t>(top_sim::code(s.contact_mode));
  out.contact_mode_name = top_sim::to_string(s.contact_mode);
  out.gap = s.gap;
  out.touching = static_cast<int64_t>(s.touching);  // LCM has no unsigned type: int64 holds all 32 bits
  out.energy = s.energy;
  out.dissipated_work = s.dissipated_work;
  out.energy_balance_residual = s.energy_balance_residual;
  out.real_time_factor = pacing.achieved;
  out.requested_real_time_factor = pacing.requested;
  out.paused = pacing.paused;
  out.fault = s.fault_message;
  out.end_state = s.end_state == top_sim::EndState::none ? "" : top_sim::to_string(s.end_state);
  out.end_state_message = s.end_message;
}

Publisher::Publisher(const std::string& url, const std::string& channel) : channel_(channel) {
  lcm_ = std::make_unique<lcm::LCM>(url);
  ok_ = lcm_->good();
  if (!ok_)
    error_ = "LCM cannot open '" + url +
             "' (for udpm:// on one machine a multicast route is needed: ip route add 224.0.0.0/4 dev lo)";
}

Publisher::~Publisher() = default;

bool Publisher::publish(const top_sim::Snapshot& s, const Pacing& pacing) {
  if (!ok_) return false;
  top_sim::top_state_t msg;
  to_lcm(s, pacing, msg);
  return lcm_->publish(channel_, &msg) == 0;
}

}  // namespace top_sim_lcm
