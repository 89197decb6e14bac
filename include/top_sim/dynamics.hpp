// Equations of motion of the full model (physics.md sections 4 and 6).
#pragma once

#include <Eigen/Core>

#include "top_sim/contact.hpp"
#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// Everything one right-hand-side evaluation derives from the state.
struct Dynamics {
  ContactKinematics contact;
  double mu = 0.0;                 // mu(s), clamped
  double normal_force = 0.0;       // N
  ContactMargins margins;
  Eigen::Vector3d contact_force = Eigen::Vector3d::Zero();   // N d = N n - mu N t_hat
  Eigen::Vector3d friction_force = Eigen::Vector3d::Zero();  // -mu N t_hat
  Eigen::Vector3d omega_dot = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_cm = Eigen::Vector3d::Zero();           // centre-of-mass acceleration
  Eigen::Vector3d a_m = Eigen::Vector3d::Zero();            // tip-sphere centre acceleration (in-plane)
  double nu_dot = 0.0;
  double dissipation = 0.0;        // W_diss' = mu N t_hat . v_t + c nu^2
  double psi_dot = 0.0;
};

// Full evaluation; the integrators use the cheaper derivative() below.
void evaluate_dynamics(const Model& model, const StateVector& y, Dynamics& out);

// dy/dt of the full model with the model's normal-force choice.
void derivative(const Model& model, const StateVector& y, StateVector& dydt);

// Finite-difference step bounds for a Jacobian: u and omega must not step across the friction kink, whose
// width is max(|v_t|, v_eps) in the contact velocity (0 = no bound for that component).
void jacobian_difference_steps(const Model& model, const StateVector& y, StateVector& max_step);

// dy/dt for whichever model kind the model selects (full or adiabatic).
void model_derivative(const Model& model, const StateVector& y, StateVector& dydt);

}  // namespace top_sim
