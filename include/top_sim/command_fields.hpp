// The schema of a run-time command, once: every number field of a Command with its name, unit, allowed range and
// meaning. Scene events, TopCommand, Python's apply, the rviz panel and dynamic_reconfigure take these fields with
// these limits (docs/interfaces.md); the friction change has its own table (friction.hpp, kFrictionParameters).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "top_sim/command.hpp"
#include "top_sim/friction.hpp"

namespace top_sim {

// Every number field of a Command, in table order: X(name). `name` is at the same time the Command member, the
// scene event key, the TopCommand field (with its set_ flag) and the key of Python's apply.
#define TOP_SIM_COMMAND_FIELDS(X) \
  X(inclination)                  \
  X(spin)                         \
  X(rotor_spin)                   \
  X(rotor_coupling)               \
  X(static_friction)              \
  X(restitution)                  \
  X(patch_radius)                 \
  X(rolling_resistance)           \
  X(spin_drag)                    \
  X(drag)

struct CommandField {
  const char* name;
  const char* unit;                      // SI; "" for a ratio
  ParameterRange range;                  // the model-independent limit (limits.hpp); validate() adds the model's
  std::string range_text;                // the allowed range as error messages give it
  const char* doc;                       // one line: what the field changes
  std::optional<double> Command::*member;
};

// The rows, in TOP_SIM_COMMAND_FIELDS order.
const std::vector<CommandField>& command_fields();

// The field called `name`, or nullptr.
const CommandField* find_command_field(const std::string& name);

// All field names joined by ", ".
std::string command_field_names();

}  // namespace top_sim
