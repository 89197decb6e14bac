// The sleeping state and its analytic results (physics.md section 5).
#include "top_sim/stationary.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "counters.hpp"

namespace top_sim {

namespace {

void add_root(std::vector<SlipRoot>& roots, const FrictionLaw& law, double s) {
  if (!(s >= 0.0 && s <= 1.0)) return;
  for (const auto& r : roots)
    if (std::abs(r.s - s) < 1e-14) return;
  roots.push_back({s, friction_slope(law, s) > 0.0});
}

}  // namespace

std::vector<SlipRoot> slip_roots(const FrictionLaw& law, double tan_alpha) {
  std::vector<SlipRoot> roots;
  const double t = std::abs(tan_alpha);
  // A law with mu(0) > tan(alpha) sticks: the regularised contact holds |v_t| ~ v_eps, i.e. s* = 0.
  if (friction_coefficient(law, 0.0) > t) roots.push_back({0.0, true});
  switch (law.kind) {
    case FrictionLawKind::paper: {
      const double disc = 1.0 - t / law.mu_c;
      if (disc >= 0.0) {
        const double q = std::sqrt(disc);
        add_root(roots, law, law.s_c * (1.0 - q));
        if (q > 0.0) {
          const double s_plus = law.s_c * (1.0 + q);
          if (s_plus <= 1.0) roots.push_back({s_plus, false});
        }
      }
      break;
    }
    case FrictionLawKind::linearized:
      if (law.k != 0.0) add_root(roots, law, law.s0 + (t - law.mu0) / law.k);
      break;
    case FrictionLawKind::coulomb:
      break;  // constant mu: no isolated balance (only the stick root above)
    case FrictionLawKind::table: {
      const auto& p = law.points;
      for (std::size_t i = 1; i < p.size(); ++i) {
        const double a = std::max(p[i - 1].second, 0.0) - t, b = std::max(p[i].second, 0.0) - t;
        if (a == b || (a * b > 0.0)) continue;  // no sign change on this segment
        const double s = p[i - 1].first + (p[i].first - p[i - 1].first) * a / (a - b);
        if (roots.empty() || std::abs(roots.back().s - s) > 1e-14) roots.push_back({s, b > a});
      }
      break;
    }
  }
  std::sort(roots.begin(), roots.end(), [](const SlipRoot& x, const SlipRoot& y) { return x.s < y.s; });
  return roots;
}

double critical_inclination(const FrictionLaw& law) { return std::atan(max_friction_coefficient(law)); }

namespace {

// Lowest stable root and the next unstable one above it; no allocation for the analytic laws
// (the adiabatic right-hand side calls this every evaluation).
bool stable_branch(const FrictionLaw& law, double tan_alpha, double& s_stable, double& s_unstable) {
  const double t = std::abs(tan_alpha);
  s_unstable = -1.0;
  if (law.kind == FrictionLawKind::paper && friction_coefficient(law, 0.0) <= t) {
    const double disc = 1.0 - t / law.mu_c;
    if (disc < 0.0) return false;
    const double q = std::sqrt(disc);
    s_stable = law.s_c * (1.0 - q);
    if (q > 0.0 && law.s_c * (1.0 + q) <= 1.0) s_unstable = law.s_c * (1.0 + q);
    return q > 0.0 || t == 0.0;  // at alpha = alpha_c the two roots merge: marginal, not stable
  }
  const auto roots = slip_roots(law, tan_alpha);
  auto stable = std::find_if(roots.begin(), roots.end(), [](const SlipRoot& r) { return r.stable; });
  if (stable == roots.end()) return false;
  s_stable = stable->s;
  auto unstable = std::find_if(stable, roots.end(), [](const SlipRoot& r) { return !r.stable; });
  if (unstable != roots.end()) s_unstable = unstable->s;
  return true;
}

double sliding_ratio_at(double slip) { return std::tan(2.0 * std::atan(slip)); }  // tan(phi+), tan(phi+/2) = s

Eigen::Vector2d downhill_direction(const Model& model) {
  const Eigen::Vector3d g_hat = model.plane.g_plane.normalized();
  const Eigen::Vector2d downhill(g_hat.x(), g_hat.y());
  return downhill.norm() > 0.0 ? Eigen::Vector2d(downhill.normalized()) : Eigen::Vector2d::Zero();
}

// The velocity u* at st.omega: rolling part R omega x n along sign(omega) h; sliding part v_h tan(phi+)
// downhill, tan(phi+/2) = s* (sliding_ratio_at).
void set_sleeping_velocity(const Model& model, double ratio, const Eigen::Vector2d& down_dir,
                           StationaryState& st) {
  const double R = model.top.tip_radius;
  const Eigen::Vector3d rolling = R * Eigen::Vector3d(st.omega.y(), -st.omega.x(), 0.0);
  st.rolling_speed = rolling.norm();
  st.sliding_speed = st.rolling_speed * ratio;
  st.velocity = Eigen::Vector2d(rolling.x(), rolling.y()) + st.sliding_speed * down_dir;
  st.phi_defined = st.rolling_speed > 0.0;
  if (st.phi_defined) {
    st.phi = travel_angle(st.velocity.x(), st.velocity.y());
  } else {
    st.reason = R == 0.0 ? "R = 0: the sleeping top does not roll, so its direction of travel phi* is undefined"
                         : "the sleeping top does not move (alpha = 0 or spin = 0): phi* is undefined";
  }
}

}  // namespace

namespace {

// The geometry of section 5 (f_hat*); false (with the reason) when f <= 0 or R sin(alpha) > f.
bool sleeping_geometry(const Model& model, StationaryState& st) {
  const double R = model.top.tip_radius;
  const double f = model.top.com_offset;
  const double alpha = model.plane.inclination;
  if (f <= 0.0) {
    std::ostringstream why;  // messages are built only on the failure paths: the adiabatic RHS calls this
    why << "com_offset f = " << f << " <= 0: the stationary solver covers ordinary tops (f > 0) only";
    st.reason = why.str();
    return false;
  }
  if (R * std::abs(std::sin(alpha)) > f) {
    std::ostringstream why;
    why << "R sin(alpha) = " << R * std::abs(std::sin(alpha)) << " m exceeds f = " << f
        << " m: the centre of mass cannot sit above the contact point, no stationary state exists";
    st.reason = why.str();
    return false;
  }
  // f_hat* = -(R/f) n + f_g g_hat puts the centre of mass vertically above the contact point.
  const Eigen::Vector3d g_hat = model.plane.g_plane.normalized();
  const double f_g = -(R / f) * std::cos(alpha) - std::sqrt(1.0 - std::pow(R * std::sin(alpha) / f, 2));
  st.f_hat = (-(R / f) * Eigen::Vector3d::UnitZ() + f_g * g_hat).normalized();
  return true;
}

}  // namespace


namespace {

// The patch law of section 12 in a sleeping top of unit spin `sign` f_hat, sliding downhill at v_d. v_eps is left
// out, as for the point contact: the law is then homogeneous of degree 0 in the speeds, so unit spin stands for all.
// gravity: g less the sleeping top's own deceleration a = u*' (it spins down): the state is the sleeping state of
// that frame, where the contact force is m (a - g).
struct PatchSetting {
  const Model& model;
  double lever;  // Rbar at N = m g cos(alpha)
  double normal_force;
  double sign;
  Eigen::Vector3d gravity;
  Eigen::Vector2d downhill;  // the direction of gravity's part in the plane
  double tan_alpha;          // |gravity in the plane| / |gravity along n|
};

PatchSetting patch_setting(const Model& model, double lever, double normal_force, double sign,
                           const Eigen::Vector3d& deceleration) {
  const Eigen::Vector3d g = model.plane.g_plane - deceleration;
  const Eigen::Vector2d in_plane(g.x(), g.y());
  const Eigen::Vector2d downhill =
      in_plane.norm() > 0.0 ? Eigen::Vector2d(in_plane.normalized()) : Eigen::Vector2d::Zero();
  return PatchSetting{model, lever, normal_force, sign, g, downhill, in_plane.norm() / std::abs(g.z())};
}

struct PatchBalance {
  bool exists = false;
  double sliding_speed = 0.0;  // v_d at unit spin
  double slip = 0.0, mu = 0.0;
  double force = 0.0;     // |F_t| / N = mu k_F v_d / |w|
  double drilling = 0.0;  // M_n / N [m]
  double max_force = 0.0;
};

PatchBalance patch_balance(const PatchSetting& ps, const Eigen::Vector3d& f_hat, double v_d) {
  const Eigen::Vector3d w = ps.sign * f_hat;
  const double R = ps.model.top.tip_radius;
  const Eigen::Vector2d rolling(R * w.y(), -R * w.x());
  const double pivot = ps.lever * std::abs(w.z()), slip_norm = std::hypot(v_d, pivot);  // |w| of section 12
  PatchBalance b;
  b.sliding_speed = v_d;
  b.slip = slip_norm / ((rolling + v_d * ps.downhill).norm() + rolling.norm() + pivot);
  b.mu = friction_coefficient(ps.model.friction, b.slip);
  const FiniteContact& fc = ps.model.finite_contact;
  const DrillingFactors k = drilling_factors(fc.law, fc.pressure, v_d, pivot);
  b.force = b.mu * k.force * v_d / slip_norm;
  b.drilling = -b.mu * ps.lever * k.torque * ps.lever * w.z() / slip_norm;
  return b;
}

// The lowest sliding speed where the law balances the weight's downhill part, mu k_F v_d / |w| = tan(alpha) (the
// stable branch: the force grows through it), scanned in q with v_d = S q / (1 - q), S = v_h + Rbar |omega_n|.
PatchBalance balancing_speed(const PatchSetting& ps, const Eigen::Vector3d& f_hat, double tan_alpha) {
  const double scale =
      ps.model.top.tip_radius * std::hypot(f_hat.x(), f_hat.y()) + ps.lever * std::abs(f_hat.z());
  auto at = [&](double q) { return patch_balance(ps, f_hat, scale * q / (1.0 - q)); };
  PatchBalance b = at(0.0);
  b.exists = tan_alpha == 0.0;  // a level plane: pure pivoting, v_d = 0
  if (b.exists) return b;
  constexpr int kScan = 256;
  double lo = 0.0, max_force = 0.0;
  for (int i = 1; i < kScan && !b.exists; ++i) {
    const double q = static_cast<double>(i) / kScan;
    const double force = at(q).force;
    max_force = std::max(max_force, force);
    if (force < tan_alpha) {
      lo = q;
      continue;
    }
    double hi = q;
    for (double mid = 0.5 * (lo + hi); mid > lo && mid < hi; mid = 0.5 * (lo + hi))
      (at(mid).force < tan_alpha ? lo : hi) = mid;
    b = at(hi);
    b.exists = true;
  }
  b.max_force = max_force;
  return b;
}

// The torque about the centre of mass of a sleeping top (contact force -m g, drilling torque M_n n) off the figure
// axis, on e1 and e2 over m g f: zero where f_hat stays put.
Eigen::Vector2d tilt_residual(const PatchSetting& ps, const Eigen::Vector3d& f_hat, const PatchBalance& b,
                              const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  const Model& m = ps.model;
  const Eigen::Vector3d rho = -(m.top.com_offset * f_hat + m.top.tip_radius * Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d torque =
      -m.top.mass * rho.cross(ps.gravity) + ps.normal_force * b.drilling * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d off_axis = torque - torque.dot(f_hat) * f_hat;
  const double scale = m.top.mass * m.plane.gravity * m.top.com_offset;
  return Eigen::Vector2d(e1.dot(off_axis), e2.dot(off_axis)) / scale;
}

// f_hat* and v_d on a patch for one sign of the spin: Newton in the tilt from the point contact's f0 (a Jacobian by
// differences), the force balance solved at each tilt. False when the law cannot hold the top at some tilt.
bool patch_tilt(const PatchSetting& ps, const Eigen::Vector3d& f0, Eigen::Vector3d& f_hat, PatchBalance& b) {
  const double tan_alpha = ps.tan_alpha;
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d e1 = n.cross(f0).norm() > 0.0 ? Eigen::Vector3d(n.cross(f0).normalized())
                                                       : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d e2 = f0.cross(e1);
  auto axis = [&](const Eigen::Vector2d& x) { return Eigen::Vector3d((f0 + x[0] * e1 + x[1] * e2).normalized()); };
  auto residual = [&](const Eigen::Vector2d& x, PatchBalance& out) {
    out = balancing_speed(ps, axis(x), tan_alpha);
    return out.exists ? tilt_residual(ps, axis(x), out, e1, e2) : Eigen::Vector2d::Zero();
  };
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  constexpr double kStep = 1e-7;  // the tilt's difference step [rad]: the residual is smooth on that scale
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::Vector2d r = residual(x, b);
    if (!b.exists) return false;
    Eigen::Matrix2d J;
    PatchBalance scratch;
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector2d dx = kStep * Eigen::Vector2d::Unit(j);
      J.col(j) = (residual(x + dx, scratch) - r) / kStep;
      if (!scratch.exists) return false;
    }
    const Eigen::Vector2d step = J.partialPivLu().solve(-r);
    if (!step.allFinite()) return false;  // a singular tilt Jacobian: no state to report rather than a NaN axis
    x += step;
    if (step.norm() < 1e-14) break;
  }
  f_hat = axis(x);
  residual(x, b);
  return b.exists;
}

}  // namespace

namespace {

// The sleeping top's spin rate on a patch (degree 0 in the spin): its energy 1/2 (I_f' + m |u_1|^2) spin^2 changes
// by the weight's power m g . u less the sliding m |g_t| v_d and the drilling -M_n omega_n (u_1: u* at unit spin).
double patch_spin_rate(const PatchSetting& ps, const StationaryState& unit, const PatchBalance& b) {
  const Model& m = ps.model;
  const double mass = m.top.mass;
  const Eigen::Vector3d& g = m.plane.g_plane;
  const double weight = mass * (g.x() * unit.velocity.x() + g.y() * unit.velocity.y());
  const double sliding = unit.friction_force * b.sliding_speed;
  const double torque = ps.sign * (weight - sliding) + unit.drilling_torque * unit.f_hat.z();
  return torque / (shell_axial_inertia(m.top) + mass * unit.velocity.squaredNorm());
}

// One sign of the spin's sleeping state on a patch (side: 0 for spin >= 0, 1 below): f_hat*, s*, mu, M_n, the
// spin rate and u* at unit spin; false when the law cannot hold the top (a critical inclination of the patch). The
// deceleration u*' = u_1 spin' it implies is fed back, three times (each changes phi* by a factor ~1e-5 less).
bool patch_side(const Model& model, const Eigen::Vector3d& f0, int side, StationaryGeometry& g) {
  const double N = model.top.mass * model.plane.gravity * std::cos(model.plane.inclination);
  const double a = patch_radius(model.finite_contact, model.top.tip_radius, N);
  const double sign = side == 0 ? 1.0 : -1.0;
  StationaryState& st = g.side[side];
  Eigen::Vector3d deceleration = Eigen::Vector3d::Zero();
  for (int pass = 0; pass < 3; ++pass) {
    const double lever = drilling_lever(model.finite_contact.pressure, a);
    const PatchSetting ps = patch_setting(model, lever, N, sign, deceleration);
    PatchBalance b;
    if (!patch_tilt(ps, f0, st.f_hat, b)) {
      std::ostringstream why;
      why << "on the patch (a = " << a << " m, Rbar = " << ps.lever << " m) the sliding friction mu(s) k_F v_d / "
          << "|w| of the sleeping top reaches at most " << b.max_force << " < tan(alpha) = " << ps.tan_alpha
          << ": no sleeping state (critical inclination with the patch about " << std::atan(b.max_force)
          << " rad, alpha_c = " << critical_inclination(model.friction) << " rad on a point contact); the top "
          << "slides downhill";
      g.state.reason = why.str();
      return false;
    }
    st.exists = true;
    st.slip = b.slip;
    st.mu = b.mu;
    st.patch_radius = a;
    st.drilling_torque = N * b.drilling;
    st.friction_force = N * b.force;
    st.omega = sign * st.f_hat;
    const double rolling = model.top.tip_radius * std::hypot(st.f_hat.x(), st.f_hat.y());
    g.side_ratio[side] = rolling > 0.0 ? b.sliding_speed / rolling : 0.0;
    g.side_downhill[side] = ps.downhill;
    set_sleeping_velocity(model, g.side_ratio[side], ps.downhill, st);
    st.spin_rate = patch_spin_rate(ps, st, b);
    const Eigen::Vector2d u_dot = sign * st.spin_rate * st.velocity;
    deceleration = Eigen::Vector3d(u_dot.x(), u_dot.y(), 0.0);
  }
  st.omega.setZero();
  st.velocity.setZero();
  st.phi = st.rolling_speed = st.sliding_speed = 0.0;
  return true;
}

StationaryGeometry solve_patch_geometry(const Model& model, StationaryGeometry g) {
  const Eigen::Vector3d f0 = g.state.f_hat;  // the point contact's, where the Newton starts
  g.patch = true;
  g.downhill = downhill_direction(model);
  g.state.exists = patch_side(model, f0, 0, g) && patch_side(model, f0, 1, g);
  g.state.slip_unstable = -1.0;  // the scan stops at the stable root
  if (!g.state.exists) g.state.f_hat = Eigen::Vector3d::UnitZ();
  return g;
}

}  // namespace

StationaryGeometry stationary_geometry(const Model& model) {
  StationaryGeometry g;
  StationaryState& st = g.state;
  if (!sleeping_geometry(model, st)) return g;
  // A patch: a Newton over force balances, solved once per model by its caller (the Simulator holds the result).
  if (model.finite_contact.has_patch()) return solve_patch_geometry(model, g);
  const double alpha = model.plane.inclination;
  if (!stable_branch(model.friction, std::tan(alpha), st.slip, st.slip_unstable)) {
    std::ostringstream why;
    why << "tan(alpha) = " << std::tan(std::abs(alpha)) << " has no stable balance mu(s*) = tan(alpha) (max mu = "
        << max_friction_coefficient(model.friction) << ", alpha_c = " << critical_inclination(model.friction)
        << " rad): the top slides downhill";
    st.reason = why.str();
    st.f_hat = Eigen::Vector3d::UnitZ();
    return g;
  }
  st.exists = true;
  g.sliding_ratio = sliding_ratio_at(st.slip);
  g.downhill = downhill_direction(model);
  return g;
}

StationaryState stationary_state(const Model& model, const StationaryGeometry& geometry, double spin) {
  count(work_counters().stationary_solves);
  if (geometry.patch && geometry.state.exists) {
    const int side = spin < 0.0 ? 1 : 0;
    StationaryState st = geometry.side[side];
    st.omega = spin * st.f_hat;
    set_sleeping_velocity(model, geometry.side_ratio[side], geometry.side_downhill[side], st);
    return st;
  }
  StationaryState st = geometry.state;
  if (!st.exists) return st;
  st.omega = spin * st.f_hat;
  set_sleeping_velocity(model, geometry.sliding_ratio, geometry.downhill, st);
  return st;
}

StationaryState stationary_state(const Model& model, double spin) {
  return stationary_state(model, stationary_geometry(model), spin);
}

StationaryState stationary_state_on_root(const Model& model, double spin, double slip) {
  StationaryState st;
  if (!sleeping_geometry(model, st)) return st;
  st.exists = true;
  st.slip = slip;
  st.omega = spin * st.f_hat;
  set_sleeping_velocity(model, sliding_ratio_at(slip), downhill_direction(model), st);
  return st;
}

StateVector stationary_state_vector(const Model& model, const StationaryState& st, double spin,
                                    const Eigen::Vector2d& position, double rotor_spin) {
  StateVector y{};
  set_position(y, position);
  set_velocity(y, st.velocity);
  set_figure_axis(y, st.f_hat);
  set_angular_velocity(y, spin * st.f_hat);
  y[idx::nu] = model.top.has_rotor ? rotor_spin - spin : 0.0;
  return y;
}

}  // namespace top_sim
