// The fast top's nutation frequency: what a step of fitted_midpoint is chosen against.
#pragma once

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// w = I_f w3 / sqrt(I_d (I_d + m f^2 sin^2 theta)) at state y [rad/s]: the figure axis's fast circling of the angular
// momentum for a top spinning at w3 about f_hat, theta from the plane normal; the tilt rate also lifts the centre of
// mass (the m f^2 term), the slow precession is left out (on the frictionless top of bench/peer_mujoco: 330.6 rad/s
// against 325.7 measured from the tilt's period). With a rotor, I_f w3 is the axial angular momentum.
double fast_top_nutation_frequency(const Model& model, const StateVector& y);

}  // namespace top_sim
