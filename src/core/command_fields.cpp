// The command schema's rows: each limit comes from limits.hpp.
#include "top_sim/command_fields.hpp"

#include "top_sim/format.hpp"
#include "top_sim/limits.hpp"

namespace top_sim {

namespace {
std::vector<CommandField> make_rows() {
  using R = ParameterRange;
  const std::string spin_text = "finite with |spin| <= " + format_number(kMaxSpin) + " [rad/s] (top_sim's spin limit)";
  const R spin_range = R::between(-kMaxSpin, false, kMaxSpin, false);
  return {
      {"inclination", "rad", R::between(-kMaxInclination, true, kMaxInclination, true),
       "finite with |alpha| < pi/2 rad", "plane inclination alpha; plane and top tilt together (plane-frame state kept)",
       &Command::inclination},
      {"spin", "rad/s", spin_range, spin_text,
       "shell spin omega . f_hat; the transverse part and the rotor's absolute spin are kept", &Command::spin},
      {"rotor_spin", "rad/s", spin_range, spin_text, "absolute rotor spin Omega (a top with a rotor only)",
       &Command::rotor_spin},
      {"rotor_coupling", "N m s", R::at_least(0.0), ">= 0 and finite [N m s]",
       "bearing coupling c of the rotor (a top with a rotor only)", &Command::rotor_coupling},
      {"static_friction", "", R::at_least(0.0), ">= mu(0) of the law in force and finite",
       "static coefficient mu_s (friction.static)", &Command::static_friction},
      {"restitution", "", R::between(0.0, false, 1.0, false), "in [0, 1]",
       "normal restitution e_N (contact.restitution); > 0 needs contact modes", &Command::restitution},
      {"patch_radius", "m", R::between(0.0, false, kMaxPatchRadius, false), "in [0, 1] m",
       "fixed contact patch radius a (contact.patch_radius), replaces hertz", &Command::patch_radius},
      {"rolling_resistance", "m", R::at_least(0.0), ">= 0 and finite",
       "rolling resistance delta (contact.rolling_resistance)", &Command::rolling_resistance},
      {"spin_drag", "N m s", R::at_least(0.0), ">= 0 and finite", "air spin drag k (air.spin_drag)",
       &Command::spin_drag},
      {"drag", "N s/m", R::at_least(0.0), ">= 0 and finite", "air drag c (air.drag)", &Command::drag},
  };
}
}  // namespace

const std::vector<CommandField>& command_fields() {
  static const std::vector<CommandField> rows = make_rows();
  return rows;
}

const CommandField* find_command_field(const std::string& name) {
  for (const CommandField& f : command_fields())
    if (name == f.name) return &f;
  return nullptr;
}

std::string command_field_names() {
  std::string names;
  for (const CommandField& f : command_fields()) names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

}  // namespace top_sim
