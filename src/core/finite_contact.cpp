// A finite contact (physics.md section 12): patch radius, drilling lever, the exact and elliptic laws, the stick set.
#include "top_sim/finite_contact.hpp"

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

double patch_radius(const FiniteContact& c, double tip_radius, double normal_force) {
  if (normal_force <= 0.0) return 0.0;
  if (!c.hertz) return c.patch_radius;
  return std::cbrt(3.0 * normal_force * tip_radius / (4.0 * c.effective_modulus));
}

double drilling_lever(PatchPressure p, double a) { return p == PatchPressure::hertz ? 3.0 * M_PI * a / 16.0 : 2.0 * a / 3.0; }

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

namespace {

// The exact law's factors on t = Rbar |omega_n| / (|v_t| + Rbar |omega_n|) in [0, 1] (t = tan(theta) / (1 +
// tan(theta)): a division, no trigonometry, per right-hand side). kNodes nodes, cubic Hermite with
// central-difference slopes stored per node (C1, so an adaptive step sees a smooth right-hand side). Built once per
// pressure, on first use (~0.1 s).
struct ExactTable {
  static constexpr int kNodes = 129;
  struct Node {
    double force, force_slope, torque, torque_slope;  // slopes per node interval
  };
  std::array<Node, kNodes> node{};
  std::array<double, kNodes> f{}, g{};  // the integrals themselves: the limit surface (f, g)(t)
  static constexpr double kStep = 1.0 / (kNodes - 1);

  explicit ExactTable(PatchPressure p) {
    const double lever = drilling_lever(p, 1.0);
    for (int i = 0; i < kNodes; ++i) {
      // The end nodes are the limits t -> 0 and 1, taken a hair inside.
      const double t = std::clamp(i * kStep, 1e-7, 1.0 - 1e-7);
      const double theta = std::atan2(t, 1.0 - t);
      const double ratio = t / ((1.0 - t) * lever);  // a omega_n / |v_t|
      const PatchIntegrals I = patch_integrals(p, ratio, 2000);
      f[i] = I.force;
      g[i] = I.torque;
      node[i].force = I.force / std::cos(theta);
      node[i].torque = I.torque / std::sin(theta);
    }
    f[0] = 1.0;
    g[0] = 0.0;
    f[kNodes - 1] = 0.0;
    g[kNodes - 1] = 1.0;
    for (int i = 0; i < kNodes; ++i) {
      const int lo = std::max(i - 1, 0), hi = std::min(i + 1, kNodes - 1);
      node[i].force_slope = (node[hi].force - node[lo].force) / (hi - lo);
      node[i].torque_slope = (node[hi].torque - node[lo].torque) / (hi - lo);
    }
  }

  DrillingFactors at(double t) const {
    const double x = std::clamp(t, 0.0, 1.0) * (kNodes - 1);
    const int i = std::min(static_cast<int>(x), kNodes - 2);
    const double u = x - i, u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = 3 * u2 - 2 * u3, h11 = u3 - u2;
    const Node& a = node[i];
    const Node& b = node[i + 1];
    return {h00 * a.force + h10 * a.force_slope + h01 * b.force + h11 * b.force_slope,
            h00 * a.torque + h10 * a.torque_slope + h01 * b.torque + h11 * b.torque_slope};
  }

  // The limit surface's point at t, by the same Hermite on the integrals (slopes by central differences).
  Eigen::Vector2d surface(double t) const {
    const double x = std::clamp(t, 0.0, 1.0) * (kNodes - 1);
    const int i = std::min(static_cast<int>(x), kNodes - 2);
    const double u = x - i;
    auto slope = [](const std::array<double, kNodes>& v, int k) {
      const int lo = std::max(k - 1, 0), hi = std::min(k + 1, kNodes - 1);
      return (v[hi] - v[lo]) / (hi - lo);
    };
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = 3 * u2 - 2 * u3, h11 = u3 - u2;
    return {h00 * f[i] + h10 * slope(f, i) + h01 * f[i + 1] + h11 * slope(f, i + 1),
            h00 * g[i] + h10 * slope(g, i) + h01 * g[i + 1] + h11 * slope(g, i + 1)};
  }
};

const ExactTable& exact_table(PatchPressure p) {
  if (p == PatchPressure::hertz) {
    static const ExactTable hertz(PatchPressure::hertz);
    return hertz;
  }
  static const ExactTable uniform(PatchPressure::uniform);
  return uniform;
}

}  // namespace

DrillingFactors drilling_factors(DrillingLaw law, PatchPressure p, double slip_speed, double pivot_speed) {
  if (law == DrillingLaw::elliptic) return {};
  const double sum = slip_speed + pivot_speed;
  return exact_table(p).at(sum > 0.0 ? pivot_speed / sum : 0.0);
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
  const ExactTable& table = exact_table(p);
  const double beta = std::atan2(my, fx);
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    const Eigen::Vector2d point = table.surface(mid);
    (std::atan2(point.y(), point.x()) < beta ? lo : hi) = mid;
  }
  return limit * (1.0 - r / table.surface(0.5 * (lo + hi)).norm());
}

}  // namespace top_sim
