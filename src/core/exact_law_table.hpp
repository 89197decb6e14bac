// The exact drilling law (physics.md section 12) as a table in t = Rbar |omega_n| / (|v_t| + Rbar |omega_n|), one
// per pressure: compiled in (exact_law_table.cpp, written by top_sim_exact_law_table from patch_integrals(); a test
// recomputes every node), so a right-hand side pays neither a quadrature nor a first-use guard.
#pragma once

#include <Eigen/Core>

#include "top_sim/finite_contact.hpp"

namespace top_sim::exact_law {

constexpr int kNodes = 129;

// On interval i (t from i / 128 to (i + 1) / 128, u = 128 t - i in [0, 1]): the law's factors (the patch
// integrals over cos(theta) and sin(theta), theta the slip angle) as cubics in u, coefficients of u^0 to u^3: a C1
// Hermite with central-difference slopes, so an adaptive step sees a smooth right-hand side. At node i: the
// integrals themselves, the limit surface (f, g)(t), (1, 0) at t = 0 and (0, 1) at t = 1.
struct Interval {
  double force[4], torque[4];
};
struct Table {
  Interval interval[kNodes - 1];
  double surface_force[kNodes], surface_torque[kNodes];
};

extern const Table kHertz;
extern const Table kUniform;

inline const Table& table(PatchPressure p) { return p == PatchPressure::hertz ? kHertz : kUniform; }

// The table by quadrature (2000 rays per node, ~0.1 s): for the generator and the test.
Table compute(PatchPressure p);

// The factors at slip speed |v_t| and pivot speed Rbar |omega_n| (both >= 0), inline: every right-hand side on a
// patch calls it. A NaN lands in the last interval (no read outside the table) and comes out NaN.
inline DrillingFactors factors(const Table& tab, double slip_speed, double pivot_speed) {
  const double sum = slip_speed + pivot_speed;
  const double x = (sum > 0.0 ? pivot_speed / sum : 0.0) * (kNodes - 1);
  const int i = x < kNodes - 1 ? static_cast<int>(x) : kNodes - 2;
  const double u = x - i;
  const double* f = tab.interval[i].force;
  const double* g = tab.interval[i].torque;
  return {((f[3] * u + f[2]) * u + f[1]) * u + f[0], ((g[3] * u + g[2]) * u + g[1]) * u + g[0]};
}

// The limit surface's point at t in [0, 1], by the same Hermite on the integrals.
Eigen::Vector2d surface(const Table& tab, double t);

}  // namespace top_sim::exact_law
