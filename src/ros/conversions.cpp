#include "conversions.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "top_sim/command_fields.hpp"
#include "top_sim/format.hpp"
#include "top_sim/plane.hpp"
#include "top_sim/trajectory.hpp"

namespace top_sim_ros {

geometry_msgs::Point point(const Eigen::Vector3d& v) {
  geometry_msgs::Point p;
  p.x = v.x(); p.y = v.y(); p.z = v.z();
  return p;
}

geometry_msgs::Vector3 vector(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 p;
  p.x = v.x(); p.y = v.y(); p.z = v.z();
  return p;
}

geometry_msgs::Quaternion quaternion(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.w = q.w(); m.x = q.x(); m.y = q.y(); m.z = q.z();
  return m;
}

namespace {

// "NAME = VALUE" of a non-finite number of `s`: the CSV column, else the fields outside the CSV.
std::string non_finite_field(const top_sim::Snapshot& s) {
  for (const top_sim::TrajectoryColumn& c : top_sim::trajectory_columns())
    if (!std::isfinite(c.value(s))) return std::string(c.name) + " = " + top_sim::format_number(c.value(s));
  return "one of pose.orientation, tip_center, friction_force, phi_star, dissipated_work";
}

}  // namespace

// The message's constants are the core's codes (msg/TopState.msg keeps their values).
static_assert(top_sim::TopState::NUTATING == top_sim::code(top_sim::Regime::nutating), "TopState regime code");
static_assert(top_sim::TopState::PRECESSING == top_sim::code(top_sim::Regime::precessing), "TopState regime code");
static_assert(top_sim::TopState::SLEEPING == top_sim::code(top_sim::Regime::sleeping), "TopState regime code");
static_assert(top_sim::TopState::SLIDING == top_sim::code(top_sim::Regime::sliding), "TopState regime code");
static_assert(top_sim::TopState::CONTACT_FAULT == top_sim::code(top_sim::Regime::contact_fault), "TopState regime code");
static_assert(top_sim::TopState::UPRIGHT == top_sim::code(top_sim::Regime::upright), "TopState regime code");
static_assert(top_sim::TopState::INVERTING == top_sim::code(top_sim::Regime::inverting), "TopState regime code");
static_assert(top_sim::TopState::INVERTED == top_sim::code(top_sim::Regime::inverted), "TopState regime code");
static_assert(top_sim::TopState::TUMBLING == top_sim::code(top_sim::Regime::tumbling), "TopState regime code");
static_assert(top_sim::TopState::ROLLING_ON_SHAPES == top_sim::code(top_sim::Regime::rolling), "TopState regime code");
static_assert(top_sim::TopState::ON_CROWN == top_sim::code(top_sim::Regime::on_crown), "TopState regime code");
static_assert(top_sim::TopState::ON_STEM == top_sim::code(top_sim::Regime::on_stem), "TopState regime code");
static_assert(top_sim::TopState::AT_REST == top_sim::code(top_sim::Regime::at_rest), "TopState regime code");
static_assert(top_sim::TopState::LYING_FLAT == top_sim::code(top_sim::Regime::lying_flat), "TopState regime code");
static_assert(top_sim::TopState::FALLEN == top_sim::code(top_sim::Regime::fallen), "TopState regime code");
static_assert(top_sim::TopState::SLIPPING == top_sim::code(top_sim::ContactMode::slipping), "TopState mode code");
static_assert(top_sim::TopState::ROLLING == top_sim::code(top_sim::ContactMode::rolling), "TopState mode code");
static_assert(top_sim::TopState::FLIGHT == top_sim::code(top_sim::ContactMode::flight), "TopState mode code");

namespace {

// The one list of the Snapshot fields TopState carries and their message fields: to_msg and to_snapshot both walk
// it, so the two maps cannot drift apart. copy(snapshot field, message field) copies one way or the other.
template <class Snap, class Msg, class Copy>
void carried_fields(Snap& s, Msg& m, Copy copy) {
  copy(s.t, m.sim_time);
  copy(s.alpha, m.alpha);
  copy(s.com, m.pose.position);
  copy(s.orientation, m.pose.orientation);
  copy(s.com_velocity, m.twist.linear);
  copy(s.angular_velocity, m.twist.angular);
  copy(s.tip_center, m.tip_center);
  copy(s.tip_velocity, m.tip_velocity);
  copy(s.contact_point, m.contact_point);
  copy(s.figure_axis, m.figure_axis);
  copy(s.spin, m.spin);
  copy(s.has_rotor, m.has_rotor);
  copy(s.rotor_spin, m.rotor_spin);
  copy(s.slip, m.slip);
  copy(s.mu, m.mu);
  copy(s.normal_force, m.normal_force);
  copy(s.friction_force, m.friction_force);
  copy(s.drilling_torque, m.drilling_torque);
  copy(s.patch_radius, m.patch_radius);
  copy(s.phi, m.phi);
  copy(s.has_stationary_state, m.has_stationary_state);
  copy(s.phi_star, m.phi_star);
  copy(s.gap, m.gap);
  copy(s.touching, m.touching);
  copy(s.energy, m.energy);
  copy(s.dissipated_work, m.dissipated_work);
  copy(s.energy_balance_residual, m.energy_balance_residual);
  copy(s.fault_message, m.fault);
  copy(s.end_message, m.end_state_message);
}

struct IntoMsg {  // snapshot field -> message field
  template <class A, class B>
  void operator()(const A& a, B& b) const { b = a; }
  void operator()(const Eigen::Vector3d& a, geometry_msgs::Point& b) const { b = point(a); }
  void operator()(const Eigen::Vector3d& a, geometry_msgs::Vector3& b) const { b = vector(a); }
  void operator()(const Eigen::Quaterniond& a, geometry_msgs::Quaternion& b) const { b = quaternion(a); }
};

struct FromMsg {  // message field -> snapshot field
  template <class A, class B>
  void operator()(A& a, const B& b) const { a = b; }
  void operator()(Eigen::Vector3d& a, const geometry_msgs::Point& b) const { a = {b.x, b.y, b.z}; }
  void operator()(Eigen::Vector3d& a, const geometry_msgs::Vector3& b) const { a = {b.x, b.y, b.z}; }
  void operator()(Eigen::Quaterniond& a, const geometry_msgs::Quaternion& b) const { a = {b.w, b.x, b.y, b.z}; }
};

}  // namespace

void to_msg(const top_sim::Snapshot& s, const ros::Time& stamp, const std::string& plane_frame,
            top_sim::TopState& out) {
  out.header.stamp = stamp;
  out.header.frame_id = plane_frame;
  carried_fields(s, out, IntoMsg());
  out.regime = top_sim::code(s.regime);
  out.regime_name = top_sim::to_string(s.regime);
  out.contact_mode = top_sim::code(s.contact_mode);
  out.contact_mode_name = top_sim::to_string(s.contact_mode);
  out.end_state = s.end_state == top_sim::EndState::none ? "" : top_sim::to_string(s.end_state);
}

namespace {

// The end state a recorded name stands for ("" is none); false for a name the core does not have.
bool end_state_named(const std::string& name, top_sim::EndState& out) {
  out = top_sim::EndState::none;
  if (name.empty()) return true;
  for (int i = 1; i < top_sim::kEndStateCount; ++i)
    if (name == top_sim::to_string(static_cast<top_sim::EndState>(i))) {
      out = static_cast<top_sim::EndState>(i);
      return true;
    }
  return false;
}

std::string end_state_names() {
  std::string names;
  for (int i = 1; i < top_sim::kEndStateCount; ++i)
    names += std::string(i > 1 ? ", " : "") + top_sim::to_string(static_cast<top_sim::EndState>(i));
  return names;
}

}  // namespace

top_sim::Snapshot to_snapshot(const top_sim::TopState& m, std::string& error) {
  top_sim::Snapshot s;
  error.clear();
  const struct {
    const char* name;
    int code, count;
  } codes[] = {{"regime", m.regime, top_sim::kRegimeCount},
               {"contact_mode", m.contact_mode, top_sim::kContactModeCount}};
  for (const auto& c : codes) {
    if (c.code >= c.count) {
      error = std::string(c.name) + " = " + std::to_string(c.code) + ": must be a code in 0.." +
              std::to_string(c.count - 1);
      return s;
    }
  }
  if (!end_state_named(m.end_state, s.end_state)) {
    error = "end_state = '" + m.end_state + "': must be empty or one of " + end_state_names();
    return s;
  }
  carried_fields(s, m, FromMsg());
  s.regime = static_cast<top_sim::Regime>(m.regime);
  s.contact_mode = static_cast<top_sim::ContactMode>(m.contact_mode);
  if (!top_sim::all_finite(s)) error = non_finite_field(s) + ": must be finite";
  return s;
}

void to_transforms(const top_sim::TopPose& s, const ros::Time& stamp, const Frames& frames,
                   geometry_msgs::TransformStamped& world_plane, geometry_msgs::TransformStamped& plane_top) {
  world_plane.header.stamp = stamp;
  world_plane.header.frame_id = frames.world;
  world_plane.child_frame_id = frames.plane;
  world_plane.transform.translation = geometry_msgs::Vector3();
  world_plane.transform.rotation = quaternion(top_sim::plane_rotation(s.alpha));
  plane_top.header.stamp = stamp;
  plane_top.header.frame_id = frames.plane;
  plane_top.child_frame_id = frames.top;
  plane_top.transform.translation = vector(s.com);
  plane_top.transform.rotation = quaternion(s.orientation.normalized());
}

void to_contact_transform(const top_sim::TopPose& s, const ros::Time& stamp, const Frames& frames,
                          geometry_msgs::TransformStamped& plane_contact) {
  plane_contact.header.stamp = stamp;
  plane_contact.header.frame_id = frames.plane;
  plane_contact.child_frame_id = frames.contact;
  plane_contact.transform.translation = vector(s.contact_point);
  plane_contact.transform.rotation = quaternion(Eigen::Quaterniond::Identity());
}

void to_grid_transform(const top_sim::TopPose& s, double pitch, const ros::Time& stamp, const Frames& frames,
                       geometry_msgs::TransformStamped& plane_grid) {
  const Eigen::Vector3d centre(pitch * std::round(s.contact_point.x() / pitch),
                               pitch * std::round(s.contact_point.y() / pitch), 0.0);
  plane_grid.header.stamp = stamp;
  plane_grid.header.frame_id = frames.plane;
  plane_grid.child_frame_id = frames.grid;
  plane_grid.transform.translation = vector(centre);
  plane_grid.transform.rotation = quaternion(Eigen::Quaterniond::Identity());
}

namespace {

double parameter_of(const top_sim::TopCommand& msg, const std::string& name) {
#define TOP_SIM_FIELD_OF_MSG(kind, field, range) \
  if (name == #field) return msg.field;
  TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_FIELD_OF_MSG)
#undef TOP_SIM_FIELD_OF_MSG
  return 0.0;
}

// The law and the parameters a TopCommand gives: those named in friction_given, else the law's nonzero ones.
std::string friction_change(const top_sim::TopCommand& msg, top_sim::FrictionChange& change) {
  top_sim::FrictionLawKind kind;
  if (!top_sim::parse_friction_law_kind(msg.friction_law, kind))
    return "friction_law = '" + msg.friction_law + "': must be one of " + top_sim::friction_law_names(", ");
  for (const std::string& name : msg.friction_given) {
    const top_sim::FrictionParameter* p = top_sim::find_friction_parameter(name);
    if (p == nullptr || p->law != kind)
      return "friction_given: '" + name + "': the " + msg.friction_law + " law reads " +
             top_sim::friction_parameter_names(kind);
    change.given.emplace_back(p, parameter_of(msg, name));
  }
  if (msg.friction_given.empty())
    for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters)
      if (p.law == kind && parameter_of(msg, p.name) != 0.0) change.given.emplace_back(&p, parameter_of(msg, p.name));
  change.kind = kind;
  if (kind != top_sim::kFrictionPointsLaw) return "";
  if (msg.table_s.size() != msg.table_mu.size()) {
    std::ostringstream os;
    os << "table_s has " << msg.table_s.size() << " values and table_mu " << msg.table_mu.size()
       << ": must have the same length";
    return os.str();
  }
  if (msg.table_s.empty()) return "";  // the table in force keeps its points
  change.points.emplace();
  for (std::size_t i = 0; i < msg.table_s.size(); ++i) change.points->emplace_back(msg.table_s[i], msg.table_mu[i]);
  return "";
}

}  // namespace

top_sim::Command command_from_message(const top_sim::TopCommand& msg, std::string& error) {
  top_sim::Command c;
  error.clear();
  // The schema's fields (command_fields.hpp), named alike in the message; the core validates their values.
#define TOP_SIM_COPY_SET_FIELD(name) \
  if (msg.set_##name) c.name = msg.name;
  TOP_SIM_COMMAND_FIELDS(TOP_SIM_COPY_SET_FIELD)
#undef TOP_SIM_COPY_SET_FIELD
  if (msg.set_friction) {
    top_sim::FrictionChange change;
    error = friction_change(msg, change);
    if (!error.empty()) return c;
    c.friction = std::move(change);
  }
  if (c.empty() && !msg.reset && !msg.set_paused)
    error = "command: no field is set (reset, set_paused, set_inclination, set_spin, ..., set_drag all false)";
  return c;
}

}  // namespace top_sim_ros
