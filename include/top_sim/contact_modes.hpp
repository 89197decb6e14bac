// Contact modes of physics.md section 9: slipping, rolling, flight; the matrix K, the rolling force, the margins
// whose sign changes are the mode-switch events, the stick impulse and the closing rule.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// The values are the contact-mode codes of the messages (TopState.msg, top_state_t.lcm) and the indexes of
// per-mode arrays; the message adapters assert them.
enum class ContactMode { slipping = 0, rolling = 1, flight = 2 };
constexpr int kContactModeCount = 3;

constexpr std::uint8_t code(ContactMode m) { return static_cast<std::uint8_t>(m); }
const char* to_string(ContactMode mode);

enum class ModeSwitchKind { lift_off, touchdown, stick, slip };

const char* to_string(ModeSwitchKind kind);

// One located mode switch (the summary's mode_switches).
struct ModeSwitch {
  double t = 0.0;
  ModeSwitchKind kind = ModeSwitchKind::lift_off;
  ContactMode from = ContactMode::slipping;
  ContactMode to = ContactMode::slipping;
  double energy_change = 0.0;  // E after - E before the switch (the stick impulse or the impact; <= 0) [J]
};

// The contact point's response of section 9: d/dt v_c = K F - b, dv_c = K P.
struct ContactResponse {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  // symmetric positive definite
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Vector3d rho = Eigen::Vector3d::Zero();    // r_t - r_cm
  Eigen::Vector3d v_c = Eigen::Vector3d::Zero();    // material velocity at the contact (3-vector)
};

ContactResponse contact_response(const Model& model, const StateVector& y);

// Rolling force F = K^-1 b (keeps v_c constant, i.e. v_t = 0 and n . v_c = 0).
Eigen::Vector3d rolling_force(const ContactResponse& r);

// |F_t| <= mu_s F_n with F_n > 0: rolling can hold with this force.
bool rolling_consistent(const Eigen::Vector3d& F, double static_friction);

// Margins that are > 0 while a mode holds; a margin falling through 0 is that mode's event (or fault).
struct ModeMargins {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double lift = kNone;      // slipping: N; rolling: F_n; flight: the gap (touchdown)
  double transfer = kNone;  // slipping: stick function max(|v_t|/v_stick - 1, (|F_t| - mu_s F_n)/(m g));
                            // rolling: (mu_s F_n - |F_t|)/(m g); flight: none
  double painleve = kNone;  // slipping: m (n . K d) (fault when <= 0)
  double end = kNone;       // in contact, the end state's margin (the run ends when < 0, tilt_end_state names it):
                            // the tip sphere's n . f_hat - cos(theta_max) (fallen), a rim's tilt sine above
                            // kFlatEndSine (lying_flat), two shapes' rest margin (at_rest); none for a ball
  double touch = kNone;     // in contact, a body with shapes: the least gap of the shapes not touching (a second
                            // shape's touchdown when <= 0)
};

// The contact force of one right-hand side, kept so that the event margins at a step's end can reuse the
// evaluation an FSAL method (dopri5) has just made there (dynamics.hpp's derivative writes it).
struct ContactForceRecord {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // F (N = F.z())
  double drilling_torque = 0.0;                      // M_n on a patch
  double painleve = ModeMargins::kNone;
};

// Applies the stick impulse P = -K^-1 (v_t, 0) to u, omega and nu (W_diss is booked by the caller); on a patch
// with a torsional impulse that stops omega_n as well (physics.md section 12).
void apply_stick_impulse(const Model& model, StateVector& y);

// The stick impulse, taken only when the stuck state's rolling force lies inside the static cone (its rolling
// transfer margin > 0): true and y stuck, else false and y untouched. A stick test at the state before the impulse
// can pass by a hair and leave a rolling state whose margin, negative from its start, is never armed.
bool stick_inside_cone(const Model& model, StateVector& y);

// Applies a contact impulse P at the contact point to u (3-vector: in-plane and gap rate), omega and nu, and on a
// patch a torsional impulse `torsion` about n [N m s].
void apply_contact_impulse(const Model& model, const Eigen::Vector3d& P, StateVector& y, double torsion = 0.0);

// Outcome of the closing rule (section 9): the mode to continue in, or a Painleve fault.
struct ClosingResult {
  ContactMode mode = ContactMode::slipping;  // slipping also when painleve: its margins carry the fault
  bool painleve = false;
  bool stuck = false;  // the stick impulse was applied to the state
};

// Closing a contact (after a plastic impact) and the initial mode: rolling if mu_s > 0, |v_t| <= v_stick and
// rolling is consistent (stick impulse applied to y); else N < 0 flight, n . K d <= 0 Painleve, else slipping.
// Models with permanent contact (static normal force, adiabatic) always slip.
ClosingResult close_contact(const Model& model, StateVector& y);

// The initial mode: flight when the gap or its rate is positive, else the closing rule.
ClosingResult initial_mode(const Model& model, StateVector& y);

// Whether the model switches modes at all (the static normal force and the adiabatic model keep the paper's
// permanent slipping contact).
bool has_contact_modes(const Model& model);

}  // namespace top_sim
