// The motion of a rigid axisymmetric body touching the plane with one of its contact shapes (physics.md sections 4,
// 9 and 13): the contact modes of section 9 with the shape's lowest point r_k as the lever and w x r_k' in the bias,
// d/dt v_c = K F - b for the material velocity at the contact v_c = v_cm + w x r_k. For the tip sphere it is the
// motion dynamics.cpp integrates (tested to agree); a point contact and air (section 12), no rotor.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "top_sim/contact.hpp"
#include "top_sim/contact_modes.hpp"
#include "top_sim/contact_shapes.hpp"
#include "top_sim/finite_contact.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// The default body: the tip sphere of tip_radius, com_offset below the centre of mass.
inline ContactShape tip_sphere(const Top& top) { return {ShapeKind::sphere, -top.com_offset, top.tip_radius}; }

struct ShapeMotion {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // F at the contact point
  Eigen::Vector3d a_cm = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega_dot = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_t = Eigen::Vector3d::Zero();  // the material velocity at the contact, in-plane
  double normal_force = 0.0;
  double mu = 0.0;           // slipping: mu(s); rolling: |F_t| / F_n; flight: 0
  double slip = 0.0;         // s of section 3, with the contact point's own velocity v_cm + r_k' for u
  double dissipation = 0.0;  // mu N t_hat . v_t while slipping (rolling does no work), and what air takes
  double painleve = ModeMargins::kNone;  // slipping: m n . K d (the fault where <= 0)
  double patch_radius = 0.0;             // a of the shape's patch (section 12), 0 without one
  double drilling_torque = 0.0;          // M_n about n of the patch
  ShapePoint point;                      // the lowest point it acts at, and its rate
};

// The patch radius at a shape's contact under normal force N (section 12): a sphere's is its own Hertz radius or the
// given contact.patch_radius; a rim is a sharp edge, so its Hertz patch is 0 (a given patch_radius applies to it too).
double shape_patch_radius(const FiniteContact& contact, const ContactShape& shape, double normal_force);

// f_hat of unit length; a rim not lying flat (contact_shapes.hpp).
ShapeMotion shape_motion(const Model& model, const ContactShape& shape, ContactMode mode, const Eigen::Vector3d& v_cm,
                         const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w);

// Two shapes touching at once (a fallen top on its tip and crown), each slipping or rolling (stuck): the unknowns
// are both contact forces, and d/dt v_k = sum_j K_kj F_j - b_k with K_kj = (1/m) 1 - [r_k]x I^-1 [r_j]x. Both
// stuck leaves the force along the line between the contacts undetermined (the body's one free rotation is about
// that line): the least-norm forces are taken, the ones without a pair of friction forces pulling against each other.
struct TwoShapeMotion {
  std::array<Eigen::Vector3d, 2> force{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<Eigen::Vector3d, 2> v_t{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<double, 2> normal_force{0.0, 0.0}, mu{0.0, 0.0}, slip{0.0, 0.0};
  std::array<double, 2> patch_radius{0.0, 0.0}, drilling_torque{0.0, 0.0};  // each slipping contact's patch
  Eigen::Vector3d a_cm = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega_dot = Eigen::Vector3d::Zero();
  double dissipation = 0.0;
  double painleve = ModeMargins::kNone;  // both slipping: > 0 iff A_kj = n . K_kj d_j is a P-matrix (unique N_k):
                                         // m min(A_11, A_22, det A / tr A)
  std::array<ShapePoint, 2> point;       // the lowest points they act at
};
TwoShapeMotion two_shape_motion(const Model& model, const std::array<ContactShape, 2>& shapes,
                                const std::array<ContactMode, 2>& modes, const Eigen::Vector3d& v_cm,
                                const Eigen::Vector3d& f_hat, const Eigen::Vector3d& w);

// ---- A body with shapes in the Simulator's state (has_shapes(model)). x and u are the reference point's in-plane
// position and velocity, r_m = r_cm - f f_hat (f = top.com_offset: the first shape's centre where it is a sphere,
// else 0 and r_m the centre of mass); gap and gap_rate are the touching shape's gap g_k = z_cm + h_k(c) and its rate
// n . v_k (model.shapes.touching: the tip sphere's gap and rate where it is the tip sphere), exactly 0 in contact.

// g_k = z_cm + h_k(c) and its rate n . v_k, the material normal velocity at its lowest point.
double shape_gap(const Model& model, const StateVector& y, const ContactShape& shape);
double shape_gap_rate(const Model& model, const StateVector& y, const ContactShape& shape);
// The shape with the least gap.
std::size_t lowest_shape(const Model& model, const StateVector& y);
// The centre of mass and its velocity in the plane frame.
Eigen::Vector3d shape_body_com(const Model& model, const StateVector& y);
Eigen::Vector3d shape_body_com_velocity(const Model& model, const StateVector& y);
// Makes `shape` the touching one: the state's gap and gap_rate become its own (the body does not move).
void retouch(Model& model, StateVector& y, std::size_t shape);
// The end state the tilt slot's margin stands for in contact: at_rest on two shapes, lying_flat on a rim, and
// fallen for a body on its tip sphere alone (its axis passed max_tilt with no shape to catch it).
inline EndState tilt_end_state(const Model& model) {
  if (!has_shapes(model)) return EndState::fallen;
  return two_touching(model.shapes) ? EndState::at_rest : EndState::lying_flat;
}
// Snapshot::touching: bit i set while shape i of top.shapes touches (a body without shapes: its tip sphere, bit 0);
// none in flight.
std::uint32_t touching_shapes(const Model& model, ContactMode mode);
// The touching shape's contact kinematics at the state y (v_t, t_hat, rolling speed, slip; contact.hpp's for the tip
// sphere): the stiff slip-onset layer and the Jacobian's difference steps read the contact's slip from here.
ContactKinematics shape_kinematics(const Model& model, const StateVector& y);
// The touching shape's motion in `mode` at the state y; and shape `shape`'s as if it alone touched.
ShapeMotion shape_motion(const Model& model, ContactMode mode, const StateVector& y);
ShapeMotion shape_motion(const Model& model, ContactMode mode, const StateVector& y, std::size_t shape);
// The least gap of the shapes not in contact and which shape has it (kNoShape and kNone when every shape touches):
// a second shape's touchdown while one touches.
double free_shape_gap(const Model& model, const StateVector& y, std::size_t& shape);
// The gap rate of that shape (0 when every shape touches): a second touchdown needs it closing.
double free_shape_gap_rate(const Model& model, const StateVector& y);
// Two shapes touching (two_touching), at the touching shape (index 0) and the second (index 1): each slipping or
// stuck as model.shapes.stuck says, or as `modes` says.
TwoShapeMotion touching_pair_motion(const Model& model, const StateVector& y);
TwoShapeMotion touching_pair_motion(const Model& model, const StateVector& y, const std::array<ContactMode, 2>& modes);
// Contact k's margin of the pair's stick or slip (section 9 at two contacts), in units of m g: stuck, its stick
// set's margin (mu_s N_k - |F_tk|) / (m g), <= 0 where it slips; slipping, > 0 until its slip speed is below the
// stick speed and the pair with k stuck holds k inside its cone. `m` is the pair's motion in its modes.
double pair_contact_margin(const Model& model, const StateVector& y, const TwoShapeMotion& m, int k);
// Section 9's stick impulse at contact k of the pair: v_k becomes 0, and the other contact keeps its normal velocity
// 0 (and, stuck, its tangential velocity 0 too).
void apply_pair_stick_impulse(const Model& model, StateVector& y, int k);
// Applies an impulse P at shape `shape`'s lowest point (and a patch's torsional impulse Q about n) to u, the touching
// shape's gap rate and omega.
void apply_shape_impulse(const Model& model, std::size_t shape, const Eigen::Vector3d& P, StateVector& y,
                         double torsion = 0.0);
// Section 9's stick impulse on the touching shape's patch: stops v_t and the pivoting omega_n, n . v_c unchanged.
void apply_shape_stick_impulse(const Model& model, StateVector& y);
// The touching shape's patch radius at normal force N.
double touching_patch_radius(const Model& model, double normal_force);
// K_kj of two_shape_motion at the state y: d v_k per newton-second at shape j's lowest point.
Eigen::Matrix3d shape_pair_response(const Model& model, const StateVector& y, std::size_t k, std::size_t j);
// The material velocity v_cm + w x r_k at shape `shape`'s lowest point.
Eigen::Vector3d shape_contact_velocity(const Model& model, const StateVector& y, std::size_t shape);
// dy/dt of the body with shapes (no rotor, a point contact, air).
void shape_derivative(const Model& model, ContactMode mode, const StateVector& y, StateVector& dydt,
                      ContactForceRecord* record, ShapeMotion* motion = nullptr);
// Section 9's K, b, lever and contact velocity at the touching shape's lowest point.
ContactResponse shape_contact_response(const Model& model, const StateVector& y);

// E of section 4 from the state, and the energy balance's scale: the kinetic energy and m g times the body's reach
// from its centre of mass (energy.cpp's for a body with shapes).
double shape_mechanical_energy(const Model& model, const StateVector& y);
double shape_energy_scale(const Model& model, const StateVector& y);

// The body's energy at centre of mass r_cm in the plane frame (section 4's E, no rotor).
double shape_body_energy(const Model& model, const Eigen::Vector3d& r_cm, const Eigen::Vector3d& v_cm, const Eigen::Vector3d& f_hat,
                         const Eigen::Vector3d& w);

}  // namespace top_sim
