// A finite contact (physics.md section 12): the patch, its coupled sliding and drilling friction, rolling
// resistance and air drag. Every term is 0 by default, and then the point contact of sections 3-4 runs unchanged.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace top_sim {

// Elastic constants of a body's surface (for patch_radius: hertz); young_modulus 0 = not given.
struct Material {
  double young_modulus = 0.0;  // E [Pa]
  double poisson_ratio = 0.0;  // nu, in (-1, 0.5]
  bool given() const { return young_modulus > 0.0; }
};

enum class PatchPressure { hertz, uniform };
enum class DrillingLaw { exact, elliptic };

const char* to_string(PatchPressure p);
const char* to_string(DrillingLaw law);

// contact.patch_radius, patch_pressure, drilling_law, rolling_resistance.
struct FiniteContact {
  double patch_radius = 0.0;       // a [m] when not hertz
  bool hertz = false;              // a = (3 N R / (4 E*))^(1/3)
  double effective_modulus = 0.0;  // E* [Pa] of the two materials (hertz only)
  PatchPressure pressure = PatchPressure::hertz;
  DrillingLaw law = DrillingLaw::exact;
  double rolling_resistance = 0.0;  // delta [m]
  bool has_patch() const { return hertz || patch_radius > 0.0; }
};

// air.spin_drag and air.drag.
struct Air {
  double spin_drag = 0.0;  // k [N m s]: torque -k omega
  double drag = 0.0;       // c [N s/m]: force -c v_cm
  bool active() const { return spin_drag + drag > 0.0; }  // both >= 0 (the scene checks): one test
};

// omega_eps of the rolling resistance's regularisation [rad/s]: far below any rolling rate a user watches.
constexpr double kRollingRateEps = 1.0e-6;

// Rolling resistance per newton of normal force: -delta omega_r / sqrt(|omega_r|^2 + omega_eps^2), omega_r the part
// of omega in the plane (n = e_z).
inline Eigen::Vector3d rolling_resistance_per_newton(double delta, const Eigen::Vector3d& w) {
  const Eigen::Vector3d w_r(w.x(), w.y(), 0.0);
  return -delta / std::sqrt(w_r.squaredNorm() + kRollingRateEps * kRollingRateEps) * w_r;
}

// 1/E* = (1 - nu_t^2)/E_t + (1 - nu_p^2)/E_p.
double effective_modulus(const Material& top, const Material& plane);

// x^(1/3) for x > 0, within 1e-14: a first guess from the exponent's bits (within 3.3 %) and two Halley steps
// (cubic convergence: 2e-5, then 7e-15). A fraction of std::cbrt's cost; a Hertz patch takes two per right-hand side.
inline double cube_root(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof x);
  bits = bits / 3 + 0x2A9F7893782DA1CEull;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  for (int k = 0; k < 2; ++k) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y;
}

// The Hertz radius a = (3 N R / (4 E*))^(1/3) at N > 0.
inline double hertz_patch_radius(const FiniteContact& c, double tip_radius, double normal_force) {
  return cube_root(0.75 * normal_force * tip_radius / c.effective_modulus);
}

// The patch radius at normal force N for a tip of radius R (0 at N <= 0: no contact, no patch).
inline double patch_radius(const FiniteContact& c, double tip_radius, double normal_force) {
  if (normal_force <= 0.0) return 0.0;
  return c.hertz ? hertz_patch_radius(c, tip_radius, normal_force) : c.patch_radius;
}

// Drilling lever Rbar: 3 pi a / 16 (Hertzian pressure) or 2 a / 3 (uniform).
inline double drilling_lever(PatchPressure p, double a) {
  return p == PatchPressure::hertz ? 3.0 * M_PI / 16.0 * a : 2.0 / 3.0 * a;
}

// The law's factors at the sliding speed |v_t| and the pivoting speed Rbar |omega_n|: with
// |w|_eps = sqrt(|v_t|^2 + Rbar^2 omega_n^2 + v_eps^2),
//   F = -mu N force v_t / |w|_eps,   M_n = -mu N Rbar torque (Rbar omega_n) / |w|_eps.
// elliptic: both 1; exact: the patch integrals divided by cos(theta) and sin(theta), theta the slip angle
// atan(Rbar |omega_n| / |v_t|), from a table.
struct DrillingFactors {
  double force = 1.0;
  double torque = 1.0;
};
DrillingFactors drilling_factors(DrillingLaw law, PatchPressure p, double slip_speed, double pivot_speed);

// The patch integrals themselves, by quadrature over the patch (for the table and the tests): |F| / (mu N) and
// |M_n| / (mu N Rbar) at a omega_n / |v_t| = ratio (ratio = inf: pure pivoting). `n` points per radius.
struct PatchIntegrals {
  double force = 0.0;
  double torque = 0.0;
};
PatchIntegrals patch_integrals(PatchPressure p, double ratio, int n = 400);

// The stick set (the law's limit surface with mu_s): mu_s N (1 - r / r_surface) [N], r the distance of
// (|F_t| / (mu_s N), |M_n| / (mu_s N Rbar)) from the origin and r_surface that of the surface in its direction;
// > 0 while a sticking patch can hold F_t and M_n (elliptic: the ellipsoid, r_surface = 1).
double stick_margin(DrillingLaw law, PatchPressure p, double tangential_force, double drilling_torque,
                    double static_friction, double normal_force, double lever);

}  // namespace top_sim
