#include "panel_logic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>

#include "control_layout.hpp"
#include "conversions.hpp"
#include "markers.hpp"
#include "top_sim/command.hpp"
#include "top_sim/command_fields.hpp"
#include "top_sim/format.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/model.hpp"

namespace top_sim_rviz {

namespace {

// "" or "FIELD = 'TEXT': must be a number" (the whole text, as std::stod would silently stop at "0.2x").
std::string parse_number(const std::string& field, const std::string& text, double& value) {
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) return field + " = '" + text + "': must be a number";
  return "";
}

bool blank(const std::string& text) { return text.find_first_not_of(" \t") == std::string::npos; }

// The friction fields as the TopCommand's law and given parameters, the law checked by the core.
std::string friction_command(const PanelFields& f, top_sim::TopCommand& out) {
  top_sim::FrictionLawKind kind;
  if (!top_sim::parse_friction_law_kind(f.friction_law, kind) || kind == top_sim::kFrictionPointsLaw)
    return "friction law = '" + f.friction_law + "': must be one of " + top_sim::friction_law_names(", ") +
           " but table (its points come from a scene)";
  out.set_friction = true;
  out.friction_law = f.friction_law;
  top_sim::FrictionLaw law;  // checks the given values; the others are the node's
  law.kind = kind;
  for (const auto& [name, text] : f.friction) {
    if (blank(text)) continue;
    const top_sim::FrictionParameter* p = top_sim::find_friction_parameter(name);
    if (p == nullptr || p->law != kind)
      return name + ": the " + f.friction_law + " law reads " + top_sim::friction_parameter_names(kind);
    double v = 0.0;
    const std::string error = parse_number(name, text, v);
    if (!error.empty()) return error;
    law.*(p->member) = v;
    out.friction_given.push_back(name);
#define TOP_SIM_SET_FIELD(kind_, field, range_) \
    if (name == #field) out.field = v;
    TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_SET_FIELD)
#undef TOP_SIM_SET_FIELD
  }
  return top_sim::validate(law);
}

}  // namespace

std::string top_name_of(const std::string& node, const std::string& top, const std::string& leaf) {
  std::string base = node.empty() || node.back() != '/' ? node : node.substr(0, node.size() - 1);
  if (!top.empty() && top != kLaunchTopName) base += "/" + top;
  return base + "/" + leaf;
}

namespace {

// One optional number field: "" (empty, or parsed into `set`, `value` and the core's check) or the parse error.
std::string number_field(const char* name, const std::string& text, std::uint8_t& set, double& value,
                         std::optional<double>& check) {
  if (blank(text)) return "";
  const std::string error = parse_number(name, text, value);
  if (!error.empty()) return error;
  set = true;
  check = value;
  return "";
}

// A contact field's flag and value in TopCommand and its member in the core's Command, by kContactFields' name.
struct ContactMembers {
  std::uint8_t top_sim::TopCommand::*set;
  double top_sim::TopCommand::*value;
  std::optional<double> top_sim::Command::*check;
};
ContactMembers contact_members(const std::string& name) {
  using M = top_sim::TopCommand;
  using C = top_sim::Command;
  if (name == "patch_radius") return {&M::set_patch_radius, &M::patch_radius, &C::patch_radius};
  if (name == "rolling_resistance") return {&M::set_rolling_resistance, &M::rolling_resistance, &C::rolling_resistance};
  if (name == "spin_drag") return {&M::set_spin_drag, &M::spin_drag, &C::spin_drag};
  return {&M::set_drag, &M::drag, &C::drag};
}

// The contact fields typed in, parsed into `out` and `check`; "" or the first parse error.
std::string contact_command(const PanelFields& f, top_sim::TopCommand& out, top_sim::Command& check) {
  for (const ContactField& field : kContactFields) {
    const auto text = f.contact.find(field.name);
    if (text == f.contact.end()) continue;
    const ContactMembers m = contact_members(field.name);
    const std::string error = number_field(field.name, text->second, out.*m.set, out.*m.value, check.*m.check);
    if (!error.empty()) return error;
  }
  return "";
}

}  // namespace

std::string fields_to_message(const PanelFields& f, top_sim::TopCommand& out) {
  out = top_sim::TopCommand();
  top_sim::Command check;
  std::string error = number_field("inclination", f.inclination, out.set_inclination, out.inclination,
                                   check.inclination);
  if (error.empty()) error = number_field("spin", f.spin, out.set_spin, out.spin, check.spin);
  if (error.empty()) error = contact_command(f, out, check);
  if (!error.empty()) return error;
  error = top_sim::validate(check, top_sim::Model());  // a full model's rules: the node checks its own again
  if (!error.empty()) return error;
  if (!blank(f.friction_law)) return friction_command(f, out);
  if (check.empty()) return "no value was typed in and no friction law picked";
  return "";
}

// The laws with scalar parameters, in the core's table order (the table law has none: it needs points).
std::vector<std::string> law_names() {
  std::vector<std::string> names;
  for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters) {
    const std::string name = top_sim::to_string(p.law);
    if (names.empty() || names.back() != name) names.push_back(name);
  }
  return names;
}

std::vector<std::string> law_parameters(const std::string& law) {
  std::vector<std::string> names;
  top_sim::FrictionLawKind kind;
  if (!top_sim::parse_friction_law_kind(law, kind)) return names;
  for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters)
    if (p.law == kind) names.push_back(p.name);
  return names;
}

std::string status_line(const top_sim::TopState& s) {
  std::string error;
  const top_sim::Snapshot snapshot = top_sim_ros::to_snapshot(s, error);
  std::string line = error.empty() ? top_sim_ros::status_text("", snapshot) : "state not readable: " + error;
  char pacing[96];
  std::snprintf(pacing, sizeof pacing, " | real time x%.2f of %s", s.real_time_factor,
                s.requested_real_time_factor > 0.0 ? top_sim::format_number(s.requested_real_time_factor).c_str()
                                                   : "as fast as possible");
  return line + pacing + (s.paused ? " | paused" : "");
}

std::string parse_real_time_factor(const std::string& text, double& value) {
  const std::string error = parse_number("real_time_factor", text, value);
  if (!error.empty()) return error + " >= 0 (0 = as fast as possible)";
  if (!std::isfinite(value) || value < 0.0)
    return top_sim::range_message("real_time_factor", value, ">= 0 and finite (0 = as fast as possible)");
  return "";
}

std::string sentence(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\n");
  if (first == std::string::npos) return "";
  std::string out = text.substr(first, text.find_last_not_of(" \t\n") + 1 - first);
  if (out[0] >= 'a' && out[0] <= 'z') out[0] = static_cast<char>(out[0] - 'a' + 'A');
  const char last = out.back();
  if (last != '.' && last != '!' && last != '?') out += '.';
  return out;
}

namespace {

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& parts) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i)
    out += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return out;
}

// "friction law coulomb with mu 0.35" (the parameters the command gives, in the core's table order).
std::string friction_part(const top_sim::TopCommand& c) {
  std::vector<std::string> given;
  for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters) {
    const std::string name = p.name;
    if (std::find(c.friction_given.begin(), c.friction_given.end(), name) == c.friction_given.end()) continue;
    double v = 0.0;
#define TOP_SIM_GET_FIELD(kind_, field, range_) \
    if (name == #field) v = c.field;
    TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_GET_FIELD)
#undef TOP_SIM_GET_FIELD
    given.push_back(name + " " + top_sim::format_number(v));
  }
  return "friction law " + c.friction_law + (given.empty() ? " with its parameters in force" : " with " + listed(given));
}

}  // namespace

std::string sent_message(const top_sim::TopCommand& c, const std::string& top) {
  std::vector<std::string> parts;
  if (c.set_inclination) parts.push_back("inclination " + top_sim::format_number(c.inclination) + " rad");
  if (c.set_spin) parts.push_back("spin " + top_sim::format_number(c.spin) + " rad/s");
  if (c.set_friction) parts.push_back(friction_part(c));
  for (const ContactField& field : kContactFields) {
    const ContactMembers m = contact_members(field.name);
    if (c.*m.set)
      parts.push_back(std::string(field.name) + " " + top_sim::format_number(c.*m.value) + " " + field_unit(field.name));
  }
  return "Sent to top '" + top + "': " + listed(parts) + ".";
}

std::string field_unit(const std::string& name) { return top_sim::find_command_field(name)->unit; }
std::string field_range(const std::string& name) { return top_sim::find_command_field(name)->range_text; }

std::string refused_message(const std::string& error) { return sentence("Nothing was sent: " + error); }

std::string service_message(const std::string& service, bool answered, bool success, const std::string& answer) {
  if (!answered) return "The service " + service + " did not answer; is the node running?";
  if (blank(answer)) return success ? "Done." : "Refused.";
  return sentence(answer);
}

std::string field_text(double value, int decimals) {
  if (decimals < 0) return top_sim::format_number(value);
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

void FollowedField::typed(const std::string& text) { edited_ = !blank(text); }

std::optional<std::string> FollowedField::follow(double value, bool has_focus) const {
  if (has_focus || edited_ || !std::isfinite(value)) return std::nullopt;
  return field_text(value, decimals_);
}

std::string inclination_from_ring(double alpha_now, double w, double x, double, double, double& alpha) {
  alpha = alpha_now + 2.0 * std::atan2(x, w);  // swing-twist: the twist of the turn about x
  top_sim::Command c;
  c.inclination = alpha;
  return top_sim::validate(c, top_sim::Model());
}

std::string spin_from_handle(double spin_now, double drag, double& spin) {
  spin = spin_now + kSpinPerMetre * drag;
  top_sim::Command c;
  c.spin = spin;
  return top_sim::validate(c, top_sim::Model());
}

double label_top(double reach) {
  constexpr double kTwoLines = 0.025;  // [m] two 8 mm lines and their spacing (markers.cpp's kLabelHeight)
  return std::max(reach + 0.02, top_sim_ros::control_layout::kTop) + kTwoLines;
}

std::optional<OrbitView> orbit_view(const std::string& camera, double distance, double current_distance,
                                    double reach) {
  OrbitView v;
  v.distance = distance > 0.0 ? distance : current_distance;
  if (camera == "low") {  // a tippe top's stem and a disc's edge show from the side, the label over them too
    v.pitch = 0.12;
    const double half_band = 0.55 * label_top(reach);  // half the plane-to-label band and a 10 % margin
    v.focal_z = 0.5 * label_top(reach);
    v.distance = std::max(v.distance, half_band / std::tan(0.5 * kFieldOfView));
  } else if (camera == "top") v.pitch = 1.45;
  else if (camera == "follow") v.pitch = 0.55;  // rviz/top_sim.rviz's
  else return std::nullopt;
  return v;
}

}  // namespace top_sim_rviz
