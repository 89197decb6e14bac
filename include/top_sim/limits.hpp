// Limits on input and on the numerics, in one place: the scene loader, command validation and the simulator
// refuse or stop at them with a message that names them (docs/reliability.md).
#pragma once

#include <cmath>

namespace top_sim {

// Largest |inclination| alpha [rad], excluded: at pi/2 the plane is a wall and carries no normal force. Scenes,
// events, commands and the tools (sweep, stability, fit) test against it; false for NaN.
constexpr double kMaxInclination = M_PI / 2;
inline bool admissible_inclination(double alpha) { return std::abs(alpha) < kMaxInclination; }

// Smallest integration step [s]: below it a step no longer changes t (double resolution at t ~ 1e4 s).
constexpr double kMinStep = 1.0e-12;

// Largest |spin| (shell or rotor) [rad/s]. A 2 cm top at 1e6 rad/s has a rim speed of 2e4 m/s, far past any
// material's bursting speed, and needs steps under 1e-8 s; beyond it the energy eventually overflows.
constexpr double kMaxSpin = 1.0e6;

// Largest fixed contact-patch radius a [m] (contact.patch_radius, the command's): a patch wider than any top. Beyond
// some 1e300 m the patch's lever times the spin overflows to inf and its slip to NaN (docs/reliability.md, bug 10).
constexpr double kMaxPatchRadius = 1.0;

// Default bound on the relative energy-balance residual |E + W_diss - E0| / scale (physics.md section 4): a
// physical motion keeps it near the integrator's tolerance (< 3e-3 in every measured setting, docs/performance.md);
// beyond this an unstable step is inventing energy, and its apparent lift-offs and falls are not physics.
constexpr double kDefaultMaxEnergyResidual = 0.1;

}  // namespace top_sim
