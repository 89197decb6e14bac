// The sleeping state and its analytic results (physics.md section 5).
#include "top_sim/stationary.hpp"

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

StationaryGeometry stationary_geometry(const Model& model) {
  StationaryGeometry g;
  StationaryState& st = g.state;
  if (!sleeping_geometry(model, st)) return g;
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
