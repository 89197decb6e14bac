// The description of one simulated system (physics.md section 1): top, plane, friction, options. A step never
// changes it; a Simulator's copy changes only by Commands between steps (plane, friction law, static friction,
// restitution, rotor coupling), and a Scene's copy never.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "top_sim/contact_shapes.hpp"
#include "top_sim/finite_contact.hpp"
#include "top_sim/friction.hpp"
#include "top_sim/plane.hpp"

namespace top_sim {

// Internal coaxial rotor of the gyroscope-loaded top (physics.md section 6).
struct Rotor {
  double inertia_axial = 0.0;  // J [kg m^2]
  double coupling = 0.0;       // c [N m s], viscous bearing
};

// Axisymmetric top with a spherical tip; all inertias about the centre of mass.
struct Top {
  double mass = 0.025;                // m [kg]
  double tip_radius = 1.5e-3;         // R [m]
  double com_offset = 0.010;          // f [m], tip-sphere centre -> centre of mass
  double inertia_axial = 5.0e-6;      // I_f [kg m^2]
  double inertia_transverse = 3.0e-6; // I_d [kg m^2]
  double max_tilt = 1.2;              // theta_max [rad]
  bool has_rotor = false;
  Rotor rotor;
  Material material;                  // young_modulus, poisson_ratio (for contact.patch_radius: hertz)
};

enum class NormalForceModel { constrained, static_approximation };
enum class ModelKind { full, adiabatic };

// model.kind auto (physics.md section 7.1): a Model's kind is then the kind in force, full until the top sleeps
// close enough to its sleeping state, adiabatic while that stays valid, full again at any command or event.
struct AutoKind {
  bool enabled = false;
  double position_tolerance = 1.0e-5;  // model.auto_tolerance: the contact point's predicted offset at handover [m]
};

// Thresholds of the regime classification (physics.md section 8).
struct RegimeThresholds {
  double nutation_angle = 1.0e-3;      // angle(omega, f_hat) above which the top nutates [rad] (physics.md: aligned to 1e-3)
  double nutation_rate = 2.0e-2;       // |d angle / dt| above which the top nutates [rad/s]
  double sleep_turn_rate = 1.0e-3;     // |a_cm| / |v_cm| below which the path is straight [1/s]
  double sleep_acceleration = 1.0e-7;  // |a_cm| below which a (slow or resting) top is asleep [m/s^2]
};

// Contact-mode settings of physics.md section 9 (scene keys friction.static and contact.*).
struct ContactSettings {
  std::optional<double> static_friction;  // mu_s when given; else mu(0) (0 with the static normal force)
  double restitution = 0.0;               // e_N in [0, 1]
  double stick_speed = 1.0e-6;            // v_stick [m/s]
  double settle_speed = 1.0e-5;           // v_settle [m/s]
};

// The parts that Commands change (Simulator::apply_now) are marked "command".
struct Model {
  Top top;                               // command: rotor.coupling
  Plane plane;                           // command: inclination (make_plane)
  FrictionLaw friction;                  // command: the whole law
  double regularization_speed = 1.0e-9;  // v_eps [m/s]
  NormalForceModel normal_force = NormalForceModel::constrained;
  ModelKind kind = ModelKind::full;     // the kind in force (switched by the Simulator under auto)
  AutoKind automatic;
  RegimeThresholds regime;
  ContactSettings contact;               // command: static_friction, restitution
  FiniteContact finite_contact;          // command: patch_radius, rolling_resistance (physics.md section 12)
  Air air;                               // command: spin_drag, drag
  Material plane_material;               // the plane file's young_modulus, poisson_ratio
  // top.shapes (physics.md section 13); count 0: the tip sphere of top.tip_radius and com_offset alone. Last: no
  // right-hand side of a tip sphere reads it.
  ShapeSet shapes;
};

// A body whose contact is not the tip sphere alone (a rim, or several shapes): its right-hand side, modes and
// events are the shapes' (shape_motion.hpp); the tip sphere's stay the same to the bit.
inline bool has_shapes(const Model& model) { return model.shapes.active; }  // one byte: every margin reads it

// True when the contact is the point of sections 3-4 with no air: the right-hand side then takes the point
// contact's code path, so every result stays the same to the bit.
inline bool point_contact(const Model& model) {
  return !model.finite_contact.has_patch() && model.finite_contact.rolling_resistance == 0.0 && !model.air.active();
}

// mu_s in force: the given value, else mu(0) of the law; 0 where the paper's permanent slipping contact holds.
double static_friction(const Model& model);

const char* to_string(NormalForceModel m);
const char* to_string(ModelKind k);
// The scene's model.kind: "auto" when the kind switches, else the kind's name.
const char* kind_name(const Model& model);

// Axial inertia the shell spins against: I_f' = I_f - J (physics.md section 6).
inline double shell_axial_inertia(const Top& top) {
  return top.inertia_axial - (top.has_rotor ? top.rotor.inertia_axial : 0.0);
}

}  // namespace top_sim
