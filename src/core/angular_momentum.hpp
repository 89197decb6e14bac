// The top's angular momentum about its centre of mass (shell and rotor), plane frame.
#pragma once

#include <Eigen/Core>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"

namespace top_sim {

// L = I_d omega_perp + (I_shell omega_f + J Omega) f_hat: the shell's transverse and axial parts and the rotor's
// spin Omega = omega_f + nu about the figure axis [kg m^2 / s].
Eigen::Vector3d angular_momentum(const Model& model, const StateVector& y);

// Azimuth of L about the plane normal [rad] (0 when L is along the normal): it turns with the precession but, unlike
// f_hat, does not nutate (the nutation is f_hat's circling of L).
double angular_momentum_azimuth(const Model& model, const StateVector& y);

}  // namespace top_sim
