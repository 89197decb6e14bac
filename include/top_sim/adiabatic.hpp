// The reduced ("adiabatic") model of physics.md section 7: the sleeping path only.
#pragma once

#include <string>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

// Empty if the adiabatic model is valid for this model (a stable stationary state exists), else why not.
std::string adiabatic_validity(const Model& model);

// dy/dt with u, f_hat and omega slaved to the stationary state of the current shell spin. `geometry` is
// stationary_geometry(model), which a caller evaluating many right-hand sides solves once (the Simulator holds it).
void adiabatic_derivative(const Model& model, const StationaryGeometry& geometry, const StateVector& y,
                          StateVector& dydt);
void adiabatic_derivative(const Model& model, const StateVector& y, StateVector& dydt);  // solves the geometry

// Puts u, f_hat and omega on the stationary manifold for the state's shell spin (keeps p, nu, W, psi).
void project_to_stationary(const Model& model, const StationaryGeometry& geometry, StateVector& y);
void project_to_stationary(const Model& model, StateVector& y);  // solves the geometry

}  // namespace top_sim
