// Validation of run-time commands: the state is never touched by a rejected one.
#include "top_sim/command.hpp"

#include <cmath>
#include <sstream>

#include "top_sim/adiabatic.hpp"

namespace top_sim {

namespace {
std::string bad(const char* field, double value, const char* range) {
  std::ostringstream os;
  os << field << " = " << value << ": must be " << range;
  return os.str();
}
}  // namespace

std::string validate(const Command& c, const Model& model) {
  if (c.inclination) {
    const double a = *c.inclination;
    if (!std::isfinite(a) || std::abs(a) >= M_PI / 2) return bad("inclination", a, "finite with |alpha| < pi/2 rad");
  }
  if (c.spin && !std::isfinite(*c.spin)) return bad("spin", *c.spin, "finite [rad/s]");
  if (c.rotor_spin) {
    if (!model.top.has_rotor) return "rotor_spin: this top has no rotor (top.rotor is not configured)";
    if (!std::isfinite(*c.rotor_spin)) return bad("rotor_spin", *c.rotor_spin, "finite [rad/s]");
  }
  if (c.rotor_coupling) {
    if (!model.top.has_rotor) return "rotor_coupling: this top has no rotor (top.rotor is not configured)";
    if (!std::isfinite(*c.rotor_coupling) || *c.rotor_coupling < 0.0)
      return bad("rotor_coupling", *c.rotor_coupling, ">= 0 and finite [N m s]");
  }
  if (c.friction) {
    const std::string e = validate(*c.friction);
    if (!e.empty()) return e;
  }
  if (model.kind == ModelKind::adiabatic && (c.inclination || c.friction)) {
    Model next = model;
    if (c.inclination) next.plane = make_plane(*c.inclination, model.plane.gravity);
    if (c.friction) next.friction = *c.friction;
    const std::string e = adiabatic_validity(next);
    if (!e.empty()) return e;
  }
  return "";
}

}  // namespace top_sim
