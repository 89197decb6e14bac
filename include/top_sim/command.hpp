// Run-time changes handed to the Simulator (scripted events, topics, services).
#pragma once

#include <optional>
#include <string>

#include "top_sim/friction.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// Each field is applied only when set; all set fields are applied together at the next step boundary.
struct Command {
  std::optional<double> inclination;     // alpha [rad]; plane and top tilt together (plane-frame state kept)
  std::optional<double> spin;            // shell omega . f_hat [rad/s]; transverse part and rotor Omega kept
  std::optional<double> rotor_spin;      // absolute rotor spin Omega [rad/s]
  std::optional<double> rotor_coupling;  // bearing coupling c [N m s]
  std::optional<FrictionChange> friction;  // over the law in force (changed_law): its kind and/or parameters
  std::optional<double> static_friction; // mu_s (friction.static), >= mu(0) of the law in force
  std::optional<double> restitution;     // e_N (contact.restitution) in [0, 1]
  // Finite contact (physics.md section 12), each >= 0: a fixed patch radius a [m] (replaces hertz), rolling
  // resistance delta [m], air spin drag k [N m s] and drag c [N s/m].
  std::optional<double> patch_radius;
  std::optional<double> rolling_resistance;
  std::optional<double> spin_drag;
  std::optional<double> drag;

  bool empty() const {
    return !inclination && !spin && !rotor_spin && !rotor_coupling && !friction && !static_friction && !restitution &&
           !patch_radius && !rolling_resistance && !spin_drag && !drag;
  }
};

// Applies each set field to the model and the state (physics.md section 8: the plane-frame state is kept; a spin
// change keeps the transverse angular velocity and the rotor's absolute spin). Validate first.
void apply_command(const Command& command, Model& model, StateVector& y);

// The model's part of apply_command: every field but spin and rotor_spin, which change the state only.
void apply_to_model(const Command& command, Model& model);

// Empty when the command can be applied to this model, else "field = value: allowed range".
std::string validate(const Command& command, const Model& model);

}  // namespace top_sim
