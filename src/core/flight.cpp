// Flight in closed form (physics.md section 9, "Flight in closed form").
#include "flight.hpp"

#include <algorithm>
#include <cmath>

#include "rigid_body.hpp"

namespace top_sim {

namespace {

// Touchdown search: samples per precession period (as the event scan's per nutation period) and per descent.
constexpr double kSamplesPerPrecession = 40.0;
constexpr double kSamplesPerDescent = 16.0;
constexpr double kMaxSamples = 1.0e7;
// Below this precession angle the spin-phase integral takes the midpoint rule (the closed form cancels there).
constexpr double kSmallAngle = 1.0e-5;

// G(phi) = integral_0^phi dphi' / (D + rho cos phi'), continuous across the branches of tan(phi / 2).
double phase_integral(double D, double rho, double phi) {
  const double k = std::sqrt((D - rho) * (D + rho));  // > 0 while f_hat stays off -n
  const double s = std::sqrt((D - rho) / (D + rho));
  const double turns = std::nearbyint(phi / (2.0 * M_PI));
  const double reduced = phi - 2.0 * M_PI * turns;
  return (2.0 * std::atan(s * std::tan(0.5 * reduced)) + 2.0 * M_PI * turns) / k;
}

// integral_t0^t dt' / (1 + f_z(t')).
double inverse_height_integral(const FlightMotion& m, double tau) {
  const double theta = m.rate * tau;
  if (std::abs(theta) < kSmallAngle) return tau / (m.D + m.rho * std::cos(0.5 * theta - m.delta));
  return (phase_integral(m.D, m.rho, theta - m.delta) - m.G0) / m.rate;
}

bool closing(const Model& model, const FlightMotion& m, double t) {
  double gap, gap_rate;
  flight_gap(model, m, t, gap, gap_rate);
  return gap <= 0.0 && gap_rate < 0.0;
}

// Time after t0 by which the centre of mass has certainly fallen to the lowest height a contact allows.
double descent_bound(const Model& model, const FlightMotion& m) {
  const Top& top = model.top;
  const double a = m.f_along * m.l_hat.z();
  const double lowest = top.tip_radius + std::min(top.com_offset * (a - m.rho), top.com_offset * (a + m.rho));
  const double drop = std::max(0.0, m.r_cm.z() - lowest);
  const double g = -model.plane.g_plane.z();
  const double vz = m.v_cm.z();
  return (vz + std::sqrt(vz * vz + 2.0 * g * drop)) / g;
}

// The first closing instant in (lo, hi] (closing at hi, with gap and rate there; not at lo) to 1e-15 relative in
// absolute time, so that the state at the answer shows it exactly: Newton on the gap, kept inside the bracket (else
// bisection); once its correction is below the tolerance, a probe half a tolerance across the root closes it.
double refine_touchdown(const Model& model, const FlightMotion& m, double lo, double hi, double gap, double gap_rate) {
  double t = hi;
  for (int i = 0; i < 200; ++i) {
    const double tol = 1e-15 * std::max(1.0, std::abs(hi));
    if (!(hi - lo > tol)) break;
    double next = gap_rate < 0.0 ? t - gap / gap_rate : 0.5 * (lo + hi);
    const bool converged = std::abs(next - t) < tol;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    flight_gap(model, m, next, gap, gap_rate);
    const bool at_root = gap <= 0.0 && gap_rate < 0.0;
    (at_root ? hi : lo) = next;
    if (converged) {  // the root is within a tolerance of next: probe its other side
      const double probe = next + (at_root ? -0.5 : 0.5) * tol;
      if (probe > lo && probe < hi) (closing(model, m, probe) ? hi : lo) = probe;
    }
    t = next;
  }
  return hi;
}

// With |gap''| <= M no touchdown comes before the root of gap + gap_rate s - M s^2 / 2 (0 unless the gap is open).
double safe_step(double gap, double gap_rate, double M) {
  if (!(gap > 0.0)) return 0.0;
  return (gap_rate + std::sqrt(gap_rate * gap_rate + 2.0 * M * gap)) / M;
}

// The bearing's part of a flight: nu decays, the shell takes up its spin (psi), the bearing dissipates c nu^2.
void apply_bearing(const Model& model, const FlightMotion& m, double tau, StateVector& y) {
  const double nu0 = m.y0[idx::nu], k = m.decay;
  y[idx::nu] = nu0 * std::exp(-k * tau);
  y[idx::psi] += m.exchange * (tau + std::expm1(-k * tau) / k);  // integral of exchange (1 - exp(-k tau'))
  y[idx::w_diss] += model.top.rotor.coupling * nu0 * nu0 * -std::expm1(-2.0 * k * tau) / (2.0 * k);
}

}  // namespace

bool flight_in_closed_form(const Model& model) {
  const Top& top = model.top;
  const bool finite_decay = !top.has_rotor || top.rotor.coupling == 0.0 ||
                            (top.rotor.inertia_axial > 0.0 && shell_axial_inertia(top) > 0.0);
  // Air acts in flight too (drag and spin drag, physics.md section 12): then F != 0 and the flight is stepped.
  return model.kind == ModelKind::full && finite_decay && model.plane.g_plane.z() < 0.0 && !has_shapes(model) &&
         !model.air.active();
}

FlightMotion flight_motion(const Model& model, const StateVector& y, double t) {
  const Top& top = model.top;
  FlightMotion m;
  m.t0 = t;
  m.y0 = y;
  const Eigen::Vector3d f_hat = figure_axis(y).normalized();
  const Eigen::Vector3d w = angular_velocity(y);
  const Eigen::Vector3d tip(y[idx::x], y[idx::x + 1], top.tip_radius + y[idx::gap]);
  m.r_cm = tip + top.com_offset * f_hat;
  m.v_cm = velocity3(y) + w.cross(top.com_offset * f_hat);
  // Section 6: L_total, constant in a torque-free flight.
  const double J = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double nu = top.has_rotor ? y[idx::nu] : 0.0;
  const double I_d = top.inertia_transverse, w_f = w.dot(f_hat);
  const Eigen::Vector3d L = detail::total_angular_momentum(top, f_hat, w, nu);
  m.axial = L.dot(f_hat);
  m.L_over_Id = L / I_d;
  m.rate = L.norm() / I_d;
  m.l_hat = m.rate > 0.0 ? Eigen::Vector3d(L.normalized()) : Eigen::Vector3d::UnitZ();
  m.body_rate = w_f - m.axial / I_d;
  m.f_along = f_hat.dot(m.l_hat);
  m.f_perp = f_hat - m.f_along * m.l_hat;
  m.f_cross = m.l_hat.cross(m.f_perp);
  m.D = 1.0 + m.f_along * m.l_hat.z();
  m.rho = std::hypot(m.f_perp.z(), m.f_cross.z());
  m.delta = std::atan2(m.f_cross.z(), m.f_perp.z());
  m.G0 = phase_integral(m.D, m.rho, -m.delta);
  if (top.has_rotor && top.rotor.coupling > 0.0) {  // physics.md: nu' = -c nu I_f / (J I_f') in flight
    m.decay = top.rotor.coupling * top.inertia_axial / (J * shell_axial_inertia(top));
    m.exchange = J * nu / top.inertia_axial;
  }
  return m;
}

void flight_gap(const Model& model, const FlightMotion& m, double t, double& gap, double& gap_rate) {
  const double tau = t - m.t0, theta = m.rate * tau;
  const double c = std::cos(theta), s = std::sin(theta);
  const double f_z = m.f_along * m.l_hat.z() + m.f_perp.z() * c + m.f_cross.z() * s;
  const double f_z_rate = m.rate * (m.f_cross.z() * c - m.f_perp.z() * s);
  const double g_z = model.plane.g_plane.z(), d = model.top.com_offset;
  gap = m.r_cm.z() + m.v_cm.z() * tau + 0.5 * g_z * tau * tau - d * f_z - model.top.tip_radius;
  gap_rate = m.v_cm.z() + g_z * tau - d * f_z_rate;
}

void flight_state(const Model& model, const FlightMotion& m, double t, StateVector& y) {
  const double tau = t - m.t0, theta = m.rate * tau, d = model.top.com_offset;
  const double c = std::cos(theta), s = std::sin(theta);
  const Eigen::Vector3d f = m.f_along * m.l_hat + c * m.f_perp + s * m.f_cross;
  const Eigen::Vector3d f_dot = m.rate * (c * m.f_cross - s * m.f_perp);  // (L / I_d) x f_hat
  const Eigen::Vector3d g = model.plane.g_plane;
  const Eigen::Vector3d tip = m.r_cm + tau * m.v_cm + (0.5 * tau * tau) * g - d * f;
  const Eigen::Vector3d u = m.v_cm + tau * g - d * f_dot;
  y = m.y0;  // without a bearing nu and W_diss stay
  set_position(y, Eigen::Vector2d(tip.x(), tip.y()));
  set_velocity(y, Eigen::Vector2d(u.x(), u.y()));
  set_figure_axis(y, f);
  const double spent = m.decay > 0.0 ? -std::expm1(-m.decay * tau) : 0.0;  // 1 - nu / nu0
  set_angular_velocity(y, m.L_over_Id + (m.body_rate + m.exchange * spent) * f);  // omega = L / I_d + sigma f_hat
  flight_gap(model, m, t, y[idx::gap], y[idx::gap_rate]);  // bit-identical to what the touchdown search saw
  // psi' = sigma + (L_z + L . f_hat) / (I_d (1 + f_z)) (orientation.hpp with omega = L / I_d + sigma f_hat).
  const double lift = m.L_over_Id.z() + m.axial / model.top.inertia_transverse;
  y[idx::psi] = m.y0[idx::psi] + m.body_rate * tau + lift * inverse_height_integral(m, tau);
  if (m.decay > 0.0) apply_bearing(model, m, tau, y);
}

double touchdown_time(const Model& model, const FlightMotion& m) {
  const double horizon = descent_bound(model, m);
  double h = horizon / kSamplesPerDescent;
  if (m.rate > 0.0) h = std::min(h, 2.0 * M_PI / m.rate / kSamplesPerPrecession);
  if (!(h > 0.0) || !std::isfinite(h)) return std::numeric_limits<double>::infinity();
  // |gap''| = |g_z - d f_z''| <= M, f_z'' = -rate^2 (f_z - f_along l_z) and |f_z - f_along l_z| <= rho.
  const double M = -model.plane.g_plane.z() + std::abs(model.top.com_offset) * m.rho * m.rate * m.rate;
  const double t_end = m.t0 + horizon + kSamplesPerDescent * h;
  double t_lo = m.t0, gap, gap_rate;
  flight_gap(model, m, t_lo, gap, gap_rate);
  for (double k = 0.0; k < kMaxSamples && t_lo < t_end; k += 1.0) {
    const double t_k = t_lo + std::max(h, safe_step(gap, gap_rate, M));
    flight_gap(model, m, t_k, gap, gap_rate);
    if (gap <= 0.0 && gap_rate < 0.0) return refine_touchdown(model, m, t_lo, t_k, gap, gap_rate);
    t_lo = t_k;
  }
  return std::numeric_limits<double>::infinity();
}

void FlightStepper::reset(const StateVector& y, double t) {
  motion_ = flight_motion(model_, y, t);
  y_ = y;
  t_ = t_previous_ = t;
  touchdown_ = touchdown_time(model_, motion_);
}

void FlightStepper::step(double t_limit) {
  t_previous_ = t_;
  t_ = std::min(touchdown_, t_limit);
  flight_state(model_, motion_, t_, y_);
  ++stats.steps;
}

}  // namespace top_sim
