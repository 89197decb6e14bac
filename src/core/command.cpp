// Validation and application of run-time commands: the state is never touched by a rejected one.
#include "top_sim/command.hpp"

#include <cmath>
#include <utility>
#include <sstream>

#include "top_sim/adiabatic.hpp"
#include "top_sim/command_fields.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/format.hpp"
#include "top_sim/limits.hpp"

namespace top_sim {

namespace {

std::string bad(const char* field, double value, const char* range) { return range_message(field, value, range); }

// The schema's model-independent limits (command_fields.hpp).
std::string validate_ranges(const Command& c) {
  for (const CommandField& f : command_fields()) {
    const std::optional<double>& v = c.*f.member;
    if (v && !f.range.admits(*v)) return bad(f.name, *v, f.range_text.c_str());
  }
  return "";
}

// physics.md section 12's run-time fields the reduced model does not carry (it does carry a patch and spin drag).
std::string validate_finite_contact(const Command& c, const Model& model) {
  if (model.kind != ModelKind::adiabatic && !model.automatic.enabled) return "";
  for (const CommandField& f : command_fields()) {
    const bool refused = f.member == &Command::rolling_resistance || f.member == &Command::drag;
    if (refused && c.*f.member && *(c.*f.member) > 0.0)
      return bad(f.name, *(c.*f.member), "0 with model.kind adiabatic or auto (the reduced model carries a patch "
                                         "and air spin drag, not rolling resistance or air drag)");
  }
  return "";
}

std::string validate_in_kind(const Command& c, const Model& model) {
  if (std::string e = validate_ranges(c); !e.empty()) return e;
  if (c.rotor_spin && !model.top.has_rotor) return "rotor_spin: this top has no rotor (top.rotor is not configured)";
  if (c.rotor_coupling && !model.top.has_rotor)
    return "rotor_coupling: this top has no rotor (top.rotor is not configured)";
  if (c.friction) {
    std::string e = validate(*c.friction, model.friction);
    if (e.empty()) e = validate(changed_law(model.friction, *c.friction));
    if (!e.empty()) return e;
  }
  if (c.restitution && *c.restitution > 0.0 && !has_contact_modes(model))
    return bad("restitution", *c.restitution, "0 with model.normal_force static or model.kind adiabatic (permanent contact)");
  if (std::string e = validate_finite_contact(c, model); !e.empty()) return e;
  if (c.static_friction || c.friction) {
    // mu_s must stay >= mu(0) of the law in force after the command.
    Model next = model;
    apply_to_model(c, next);
    const double mu0 = friction_coefficient(next.friction, 0.0);
    if (c.static_friction) {
      const double v = *c.static_friction;
      if (!std::isfinite(v) || v < mu0) {
        std::ostringstream range;
        range << ">= mu(0) = " << format_number(mu0) << " of law " << to_string(next.friction.kind) << " and finite";
        return bad("static_friction", v, range.str().c_str());
      }
      if (v > 0.0 && !has_contact_modes(model))
        return bad("static_friction", v, "0 with model.normal_force static or model.kind adiabatic (no rolling)");
    } else if (next.contact.static_friction && *next.contact.static_friction < mu0) {
      std::ostringstream os;
      os << "friction: law " << to_string(next.friction.kind) << " has mu(0) = " << format_number(mu0)
         << " above the static coefficient in force (friction.static = "
         << format_number(*next.contact.static_friction) << "); set static_friction >= " << format_number(mu0)
         << " in the same command";
      return os.str();
    }
  }
  if (model.kind == ModelKind::adiabatic && (c.inclination || c.friction || c.patch_radius)) {
    Model next = model;
    apply_to_model(c, next);  // the model the command would leave
    const std::string e = adiabatic_validity(next);
    if (!e.empty()) return e;
  }
  return "";
}

}  // namespace

std::string validate(const Command& c, const Model& model) {
  // Under model.kind auto a command always lands in the full model (physics.md section 7.1): judge it there.
  if (model.automatic.enabled && model.kind != ModelKind::full) {
    Model full = model;
    full.kind = ModelKind::full;
    return validate_in_kind(c, full);
  }
  return validate_in_kind(c, model);
}

void apply_to_model(const Command& c, Model& model) {
  if (c.inclination) model.plane = make_plane(*c.inclination, model.plane.gravity);
  if (c.friction) model.friction = changed_law(model.friction, *c.friction);
  if (c.static_friction) model.contact.static_friction = *c.static_friction;
  if (c.restitution) model.contact.restitution = *c.restitution;
  if (c.rotor_coupling) model.top.rotor.coupling = *c.rotor_coupling;
  if (c.patch_radius) {
    model.finite_contact.hertz = false;
    model.finite_contact.patch_radius = *c.patch_radius;
  }
  if (c.rolling_resistance) model.finite_contact.rolling_resistance = *c.rolling_resistance;
  if (c.spin_drag) model.air.spin_drag = *c.spin_drag;
  if (c.drag) model.air.drag = *c.drag;
}

void apply_command(const Command& c, Model& model, StateVector& y) {
  apply_to_model(c, model);
  const double spin = shell_spin(y);
  if (c.spin) {
    const double rotor_spin = spin + y[idx::nu];
    set_angular_velocity(y, angular_velocity(y) + (*c.spin - spin) * figure_axis(y).normalized());
    if (model.top.has_rotor) y[idx::nu] = rotor_spin - *c.spin;  // the rotor keeps its absolute spin
  }
  if (c.rotor_spin) y[idx::nu] = *c.rotor_spin - shell_spin(y);
}

}  // namespace top_sim
