// Equations of motion of the full model in each contact mode (physics.md sections 4, 6 and 9).
#pragma once

#include <Eigen/Core>

#include "top_sim/contact.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// What a point contact's right-hand side derives from the state (a right-hand side of the point contact fills only
// this: the finite contact's fields below would cost it a zeroing per evaluation).
struct PointContactDynamics {
  ContactKinematics contact;       // from the in-plane velocities (in flight: what touchdown would see)
  double mu = 0.0;                 // slipping: mu(s), clamped; rolling: the mobilised |F_t| / F_n; flight: 0
  double normal_force = 0.0;       // N = F_n (0 in flight)
  Eigen::Vector3d contact_force = Eigen::Vector3d::Zero();   // F at the contact point
  Eigen::Vector3d friction_force = Eigen::Vector3d::Zero();  // its in-plane part
  Eigen::Vector3d omega_dot = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_cm = Eigen::Vector3d::Zero();           // centre-of-mass acceleration
  Eigen::Vector3d a_m = Eigen::Vector3d::Zero();            // tip-sphere centre acceleration (z: flight only)
  double nu_dot = 0.0;
  double dissipation = 0.0;        // W_diss' = mu N t_hat . v_t + c nu^2 (friction does no work while rolling)
  double psi_dot = 0.0;
};

// The finite contact's terms (physics.md section 12); all 0 for a point contact.
struct ContactDynamics : PointContactDynamics {
  double patch_radius = 0.0;       // a [m]
  double drilling_torque = 0.0;    // n . M_n [N m]
  Eigen::Vector3d couple = Eigen::Vector3d::Zero();  // M_n n + M_r: the contact's torque besides rho x F [N m]
  Eigen::Vector3d air_force = Eigen::Vector3d::Zero();   // -c v_cm [N]
  Eigen::Vector3d air_torque = Eigen::Vector3d::Zero();  // -k omega [N m]
};

// Everything one evaluation derives from the state: the motion, the finite contact's terms and the mode's margins
// (a right-hand side fills a ContactDynamics: it needs no margins).
struct Dynamics : ContactDynamics {
  ModeMargins margins;             // filled by evaluate_dynamics only
};

// The force (and, on a patch, the drilling torque) that keeps a contact stuck: v_c constant and, on a patch,
// omega_n constant too (physics.md sections 9 and 12). A point contact: F = K^-1 b.
struct StickForce {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double drilling_torque = 0.0;
};
StickForce stick_force(const Model& model, const StateVector& y);

// How far a stuck contact is inside its stick set [N] (> 0: it holds): mu_s F_n - |F_t| for a point, the law's
// limit surface on a patch (finite_contact.hpp).
double stick_margin(const Model& model, const StickForce& stick);
// The patch radius of the contact that may stick, at normal force N: the tip sphere's, or the touching shape's.
double stick_patch_radius(const Model& model, double normal_force);

// Jellett's quantity lambda = L . (f f_hat + R n) [kg m^3 / s]: conserved on a point contact without air; on a
// finite contact d lambda / dt = (couple + air_torque) . (f f_hat + R n) (physics.md section 12).
double jellett(const Model& model, const StateVector& y);

// Full evaluation in `mode`, including the margins of that mode. `cos_max_tilt` = cos(model.top.max_tilt), which
// a caller evaluating many states of one model (the Simulator's event scans) computes once.
void evaluate_dynamics(const Model& model, ContactMode mode, const StateVector& y, Dynamics& out, double cos_max_tilt);
void evaluate_dynamics(const Model& model, ContactMode mode, const StateVector& y, Dynamics& out);

// ContactForceRecord: contact_modes.hpp.
// dy/dt of the full model in `mode` with the model's normal-force choice (allocation-free).
void derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                ContactForceRecord* record = nullptr);

// The margins of `mode` from a recorded contact force (no dynamics evaluation); evaluate_dynamics() uses it too.
// Returns false for a slipping contact with mu_s > 0, whose stick function (left at kNone) needs the rolling force.
bool margins_from_record(const Model& model, ContactMode mode, const StateVector& y, const ContactForceRecord& r,
                         double cos_max_tilt, ModeMargins& out);

// Finite-difference step bounds for a Jacobian: u and omega must not step across the friction kink, whose
// width is max(|v_t|, v_eps) in the contact velocity (0 = no bound, < 0 = the column is identically zero).
void jacobian_difference_steps(const Model& model, ContactMode mode, const StateVector& y, StateVector& max_step);

// dy/dt for whichever model kind the model selects (full or adiabatic).
void model_derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                      ContactForceRecord* record = nullptr);

// The contact's model, decided once: a caller that integrates many steps of one model (the Simulator, at each
// restart) passes it, and the right-hand side then runs only the code that model needs. `patch`: a patch (fixed or
// Hertz) alone; `finite`: any section-12 term, rolling resistance and air included.
// `shapes`: a body whose contact is not the tip sphere alone (has_shapes, shape_motion.hpp).
enum class ContactModel : unsigned char { point, patch, finite, shapes };
inline ContactModel contact_model(const Model& model) {
  if (has_shapes(model)) return ContactModel::shapes;
  if (point_contact(model)) return ContactModel::point;
  const bool patch_alone = model.finite_contact.rolling_resistance == 0.0 && !model.air.active();
  return patch_alone ? ContactModel::patch : ContactModel::finite;
}
void model_derivative(const Model& model, ContactModel contact, ContactMode mode, const StateVector& y,
                      StateVector& dydt, ContactForceRecord* record = nullptr);

}  // namespace top_sim
