// A finite contact (physics.md section 12): patch radius, drilling lever, the exact and elliptic laws, the stick set.
#include "top_sim/finite_contact.hpp"

#include "exact_law_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace top_sim {

const char* to_string(PatchPressure p) { return p == PatchPressure::hertz ? "hertz" : "uniform"; }
const char* to_string(DrillingLaw law) { return law == DrillingLaw::exact ? "exact" : "elliptic"; }

double effective_modulus(const Material& t, const Material& p) {
  if (!t.given() || !p.given()) return 0.0;
  return 1.0 / ((1.0 - t.poisson_ratio * t.poisson_ratio) / t.young_modulus +
                (1.0 - p.poisson_ratio * p.poisson_ratio) / p.young_modulus);
}

namespace {

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n), for the radial integrals along a ray.
template <int N>
struct GaussLegendre {
  std::array<double, N> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < N; ++i) {
      double z = std::cos(M_PI * (i + 0.75) / (N + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = 0.0;
        for (int k = 1; k <= N; ++k) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
        }
        dp = N * (z * p0 - p1) / (z * z - 1.0);
        const double dz = p0 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-15) break;
      }
      x[i] = z;
      w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

}  // namespace

// Unit patch (a = 1), v_t = (V, 0), omega_n = w > 0: the slip field is a rotation about rho0 = (0, V/w), so along
// each ray from rho0 (direction e) the slip direction n x e is constant; only the pressure varies along the ray.
// F = -mu sum over rays of (n x e) int p r dr, M_n = -mu sum of int p (rho0 . e + r) r dr.
PatchIntegrals patch_integrals(PatchPressure pressure, double ratio, int n) {
  PatchIntegrals out;
  if (!(ratio > 0.0)) {  // pure sliding
    out.force = 1.0;
    return out;
  }
  static const GaussLegendre<24> gl;
  const double c = std::isinf(ratio) ? 0.0 : 1.0 / ratio;  // |rho0|
  const double total = pressure == PatchPressure::hertz ? 2.0 * M_PI / 3.0 : M_PI;  // N of p = sqrt(1 - r^2) or 1
  // Rays that meet the disk: all when rho0 is inside, else a cone of half angle asin(1/c) about -rho0.
  const bool inside = c < 1.0;
  const double centre = -M_PI / 2.0, half = inside ? M_PI : std::asin(1.0 / c);
  double Fx = 0.0, M = 0.0;
  for (int k = 0; k < n; ++k) {
    const double psi = centre + half * (-1.0 + (2.0 * k + 1.0) / n);  // midpoints: periodic or vanishing ends
    const double ey = std::sin(psi);
    const double b = c * ey;                            // rho0 . e
    const double disc = b * b - c * c + 1.0;            // |rho0 + r e|^2 = 1 at r = -b +- sqrt(disc)
    if (disc <= 0.0) continue;
    const double r_hi = -b + std::sqrt(disc), r_lo = std::max(0.0, -b - std::sqrt(disc));
    if (r_hi <= r_lo) continue;
    // p = sqrt((r - r_-)(r_+ - r)) for hertz: r = m + h cos(phi) makes it h sin(phi), smooth in phi.
    const double m = -b, h = std::sqrt(disc);
    const double phi_lo = 0.0, phi_hi = std::acos(std::clamp((r_lo - m) / h, -1.0, 1.0));
    double I1 = 0.0, I2 = 0.0;  // int p r dr, int p r^2 dr
    for (int j = 0; j < 24; ++j) {
      const double phi = 0.5 * (phi_hi + phi_lo) + 0.5 * (phi_hi - phi_lo) * gl.x[j];
      const double r = m + h * std::cos(phi), dr = h * std::sin(phi) * 0.5 * (phi_hi - phi_lo) * gl.w[j];
      const double p = pressure == PatchPressure::hertz ? h * std::sin(phi) : 1.0;
      I1 += p * r * dr;
      I2 += p * r * r * dr;
    }
    const double dpsi = 2.0 * half / n;
    Fx += -(-ey) * I1 * dpsi;  // slip direction n x e = (-ey, ex); F = -(its integral)
    M += -(b * I1 + I2) * dpsi;
  }
  const double lever = drilling_lever(pressure, 1.0);
  out.force = std::abs(Fx) / total;
  out.torque = std::abs(M) / (total * lever);
  return out;
}

namespace exact_law {

// Cubic Hermite coefficients in u of values p and slopes m (per interval) at the two ends.
void hermite(double p0, double m0, double p1, double m1, double (&c)[4]) {
  c[0] = p0;
  c[1] = m0;
  c[2] = 3.0 * (p1 - p0) - 2.0 * m0 - m1;
  c[3] = 2.0 * (p0 - p1) + m0 + m1;
}

// The end nodes are the limits t -> 0 and 1, taken a hair inside; slopes are central differences (one-sided at
// the ends).
Table compute(PatchPressure p) {
  Table tab{};
  const double lever = drilling_lever(p, 1.0), step = 1.0 / (kNodes - 1);
  double force[kNodes], torque[kNodes];
  for (int i = 0; i < kNodes; ++i) {
    const double t = std::clamp(i * step, 1e-7, 1.0 - 1e-7);
    const double theta = std::atan2(t, 1.0 - t);
    const PatchIntegrals I = patch_integrals(p, t / ((1.0 - t) * lever), 2000);  // at a omega_n / |v_t|
    force[i] = I.force / std::cos(theta);
    torque[i] = I.torque / std::sin(theta);
    tab.surface_force[i] = i == 0 ? 1.0 : i == kNodes - 1 ? 0.0 : I.force;
    tab.surface_torque[i] = i == 0 ? 0.0 : i == kNodes - 1 ? 1.0 : I.torque;
  }
  auto slope = [](const double* v, int k) {
    const int lo = std::max(k - 1, 0), hi = std::min(k + 1, kNodes - 1);
    return (v[hi] - v[lo]) / (hi - lo);
  };
  for (int i = 0; i + 1 < kNodes; ++i) {
    hermite(force[i], slope(force, i), force[i + 1], slope(force, i + 1), tab.interval[i].force);
    hermite(torque[i], slope(torque, i), torque[i + 1], slope(torque, i + 1), tab.interval[i].torque);
  }
  return tab;
}

Eigen::Vector2d surface(const Table& tab, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * (kNodes - 1);
  const int i = std::min(static_cast<int>(x), kNodes - 2);
  Eigen::Vector2d out;
  int k = 0;
  for (const double* v : {tab.surface_force, tab.surface_torque}) {
    auto slope = [v](int j) {
      const int lo = std::max(j - 1, 0), hi = std::min(j + 1, kNodes - 1);
      return (v[hi] - v[lo]) / (hi - lo);
    };
    double c[4];
    hermite(v[i], slope(i), v[i + 1], slope(i + 1), c);
    const double u = x - i;
    out[k++] = ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
  }
  return out;
}

}  // namespace exact_law

DrillingFactors drilling_factors(DrillingLaw law, PatchPressure p, double slip_speed, double pivot_speed) {
  if (law == DrillingLaw::elliptic) return {};
  return exact_law::factors(exact_law::table(p), slip_speed, pivot_speed);
}

double stick_margin(DrillingLaw law, PatchPressure p, double tangential_force, double drilling_torque,
                    double static_friction, double normal_force, double lever) {
  const double limit = static_friction * normal_force;
  if (!(limit > 0.0)) return -std::abs(tangential_force) - std::abs(drilling_torque) - 1.0;
  const double fx = std::abs(tangential_force) / limit;
  const double my = lever > 0.0 ? std::abs(drilling_torque) / (limit * lever) : 0.0;
  const double r = std::hypot(fx, my);
  if (law == DrillingLaw::elliptic || r == 0.0) return limit * (1.0 - r);
  // The limit surface (f, g)(t) turns monotonically from (1, 0) to (0, 1): find its point in the
  // direction of (fx, my) by bisection on the table's angle.
  const exact_law::Table& table = exact_law::table(p);
  const double beta = std::atan2(my, fx);
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    const Eigen::Vector2d point = exact_law::surface(table, mid);
    (std::atan2(point.y(), point.x()) < beta ? lo : hi) = mid;
  }
  return limit * (1.0 - r / exact_law::surface(table, 0.5 * (lo + hi)).norm());
}

}  // namespace top_sim
