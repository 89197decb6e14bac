// Linear stability of the sleeping state (physics.md section 10).
#include "top_sim/stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>

#include "top_sim/dynamics.hpp"
#include "top_sim/finite_contact.hpp"
#include "top_sim/format.hpp"

namespace top_sim {

ReducedCoordinates reduced_coordinates(const Model& model, const Eigen::Vector3d& f_star) {
  ReducedCoordinates rc;
  rc.rotor = model.top.has_rotor;
  rc.f_star = f_star.normalized();
  // e1 along n x f_star (the in-plane horizontal h when f_star leans downhill); any axis when upright.
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitZ().cross(rc.f_star);
  if (e1.norm() < 1e-3) e1 = Eigen::Vector3d::UnitX() - rc.f_star.x() * rc.f_star;
  rc.e1 = e1.normalized();
  rc.e2 = rc.f_star.cross(rc.e1);
  return rc;
}

StateVector expand(const ReducedCoordinates& rc, const Eigen::VectorXd& z) {
  StateVector y{};
  set_velocity(y, Eigen::Vector2d(z[0], z[1]));
  const double a = z[2], b = z[3];
  set_figure_axis(y, a * rc.e1 + b * rc.e2 + std::sqrt(std::max(0.0, 1.0 - a * a - b * b)) * rc.f_star);
  set_angular_velocity(y, Eigen::Vector3d(z[4], z[5], z[6]));
  if (rc.rotor) y[idx::nu] = z[7];
  return y;
}

Eigen::VectorXd reduce(const ReducedCoordinates& rc, const StateVector& y) {
  Eigen::VectorXd z(rc.size());
  const Eigen::Vector3d f = figure_axis(y).normalized();
  z << y[idx::u], y[idx::u + 1], rc.e1.dot(f), rc.e2.dot(f), y[idx::omega], y[idx::omega + 1], y[idx::omega + 2],
      Eigen::VectorXd::Constant(rc.rotor ? 1 : 0, y[idx::nu]);
  return z;
}

Eigen::VectorXd reduce_rate(const ReducedCoordinates& rc, const StateVector& dydt) {
  const Eigen::Vector3d f_dot = figure_axis(dydt);
  Eigen::VectorXd r(rc.size());
  r << dydt[idx::u], dydt[idx::u + 1], rc.e1.dot(f_dot), rc.e2.dot(f_dot), dydt[idx::omega], dydt[idx::omega + 1],
      dydt[idx::omega + 2], Eigen::VectorXd::Constant(rc.rotor ? 1 : 0, dydt[idx::nu]);
  return r;
}

namespace {

// Below this many v_eps of sleeping speed the regularisation, not the friction law, sets the friction.
constexpr double kRegularisedSpeeds = 100.0;

// F(z): the reduced right-hand side of the slipping contact.
Eigen::VectorXd reduced_rate(const Model& model, const ReducedCoordinates& rc, const Eigen::VectorXd& z) {
  StateVector dydt{};
  derivative(model, ContactMode::slipping, expand(rc, z), dydt);
  return reduce_rate(rc, dydt);
}

// The scale of each coordinate (StabilityOptions).
Eigen::VectorXd difference_scales(const Model& model, const ReducedCoordinates& rc, const StateVector& y) {
  const Eigen::Vector3d w = angular_velocity(y);
  const ContactKinematics k = contact_kinematics(model, in_plane_velocity(y), w);
  // With a patch the friction turns on the scale of the generalised slip |w| = |(v_t, Rbar omega_n)| (section 12):
  // at an upright top v_t = 0 and Rbar |omega_n| is the width; Rbar = 0 for a point contact (unchanged there).
  const FiniteContact& fc = model.finite_contact;
  const double weight = model.top.mass * model.plane.gravity * std::cos(model.plane.inclination);
  const double lever =
      fc.has_patch() ? drilling_lever(fc.pressure, patch_radius(fc, model.top.tip_radius, weight)) : 0.0;
  const double width = std::max({k.v_t.norm(), lever * std::abs(w.z()), model.regularization_speed});
  const double R = model.top.tip_radius;
  const double spin_scale = std::max(w.norm(), 1.0);
  const double omega_scale = R > 0.0 ? std::min(width / R, spin_scale) : spin_scale;
  const double rotor_scale = std::max(spin_scale, std::abs(y[idx::nu] + w.dot(rc.f_star)));
  Eigen::VectorXd scale(rc.size());
  scale << width, width, 1.0, 1.0, omega_scale, omega_scale, omega_scale,
      Eigen::VectorXd::Constant(rc.rotor ? 1 : 0, rotor_scale);
  return scale;
}

Eigen::MatrixXd central_difference(const Model& model, const ReducedCoordinates& rc, const Eigen::VectorXd& z0,
                                   const Eigen::VectorXd& h) {
  const int n = rc.size();
  Eigen::MatrixXd J(n, n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd zp = z0, zm = z0;
    zp[j] += h[j];
    zm[j] -= h[j];
    J.col(j) = (reduced_rate(model, rc, zp) - reduced_rate(model, rc, zm)) / (zp[j] - zm[j]);  // the step taken
  }
  return J;
}

}  // namespace

Eigen::MatrixXd reduced_jacobian(const Model& model, const StateVector& y, const StabilityOptions& options) {
  const ReducedCoordinates rc = reduced_coordinates(model, figure_axis(y));
  const Eigen::VectorXd z0 = reduce(rc, y);
  const Eigen::VectorXd h = options.step * difference_scales(model, rc, y);
  if (!options.richardson) return central_difference(model, rc, z0, h);
  return (4.0 * central_difference(model, rc, z0, 0.5 * h) - central_difference(model, rc, z0, h)) / 3.0;
}

namespace {

bool by_real_part(Eigenvalue a, Eigenvalue b) {
  return a.real() > b.real() || (a.real() == b.real() && a.imag() > b.imag());
}

// Removes the eigenvalue of `pool` nearest to `target`, and its conjugate if complex; returns it with Im >= 0.
Eigenvalue take_nearest(std::vector<Eigenvalue>& pool, Eigenvalue target) {
  if (pool.empty()) return {NAN, NAN};
  auto nearest = [&pool](Eigenvalue t) {
    return std::min_element(pool.begin(), pool.end(),
                            [t](Eigenvalue a, Eigenvalue b) { return std::abs(a - t) < std::abs(b - t); });
  };
  const Eigenvalue v = *nearest(target);
  pool.erase(nearest(v));
  if (v.imag() != 0.0 && !pool.empty()) pool.erase(nearest(std::conj(v)));
  return {v.real(), std::abs(v.imag())};
}

struct Spectrum {
  std::vector<Eigenvalue> eigenvalues;
  Eigenvalue zero;
  StabilityModes modes;
};

// zero: the smallest |lambda|; nutation: nearest i |L . f| / I_d; bearing (rotor): nearest -c (1/J + 1/I_f');
// precession: nearest i m g f / |L . f|; friction: the rest.
Spectrum classified_spectrum(const Model& model, const Eigen::MatrixXd& J, double spin, double rotor_spin) {
  Spectrum s;
  const Eigen::VectorXcd ev = Eigen::EigenSolver<Eigen::MatrixXd>(J, false).eigenvalues();
  s.eigenvalues.assign(ev.data(), ev.data() + ev.size());
  std::sort(s.eigenvalues.begin(), s.eigenvalues.end(), by_real_part);
  std::vector<Eigenvalue> pool = s.eigenvalues;
  auto zero = std::min_element(pool.begin(), pool.end(), [](Eigenvalue a, Eigenvalue b) { return std::abs(a) < std::abs(b); });
  s.zero = *zero;
  pool.erase(zero);
  const Top& top = model.top;
  const double J_r = top.has_rotor ? top.rotor.inertia_axial : 0.0;
  const double axial_momentum = std::abs(shell_axial_inertia(top) * spin + J_r * rotor_spin);  // |L_total . f_hat|
  s.modes.nutation = take_nearest(pool, {0.0, axial_momentum / top.inertia_transverse});
  if (top.has_rotor) {
    const double rate = top.rotor.coupling * (1.0 / J_r + 1.0 / shell_axial_inertia(top));
    s.modes.bearing.push_back(take_nearest(pool, {-rate, 0.0}));
  }
  const double weight_torque = top.mass * model.plane.gravity * top.com_offset;
  s.modes.precession = take_nearest(pool, {0.0, axial_momentum > 0.0 ? weight_torque / axial_momentum : 0.0});
  std::sort(pool.begin(), pool.end(), by_real_part);
  s.modes.friction = pool;
  return s;
}

double largest_real_but_zero(const Spectrum& s) {
  double max_real = -INFINITY;
  bool skipped = false;
  for (const Eigenvalue& v : s.eigenvalues) {
    if (!skipped && v == s.zero) {
      skipped = true;
      continue;
    }
    max_real = std::max(max_real, v.real());
  }
  return max_real;
}

}  // namespace

namespace {

// The spectrum of the full model `model` at the state y (shell spin r.spin, rotor r.rotor_spin): fills r.
void analyse_state(const Model& model, const StateVector& y, const StabilityOptions& options, StabilityResult& r) {
  r.exists = true;
  r.jacobian = reduced_jacobian(model, y, options);
  const ReducedCoordinates rc = reduced_coordinates(model, figure_axis(y));
  r.residual = reduced_rate(model, rc, reduce(rc, y)).norm();
  const Spectrum s = classified_spectrum(model, r.jacobian, r.spin, r.rotor_spin);
  r.eigenvalues = s.eigenvalues;
  r.zero = s.zero;
  r.modes = s.modes;
  r.max_real = largest_real_but_zero(s);
  r.stable = r.max_real < -options.stability_tolerance;
  r.relaxation_time = 1.0 / std::abs(r.modes.precession.real());
  // The error estimate: the same analysis at twice the step.
  StabilityOptions doubled = options;
  doubled.step *= 2.0;
  const Spectrum s2 = classified_spectrum(model, reduced_jacobian(model, y, doubled), r.spin, r.rotor_spin);
  r.precession_error = std::abs(s2.modes.precession.real() - r.modes.precession.real());
  r.resolved = r.precession_error <= 0.01 * std::abs(r.modes.precession.real());
}

}  // namespace

StabilityResult stability_at(const Model& model_in, const StationaryState& st, double spin, double rotor_spin,
                             const StabilityOptions& options) {
  StabilityResult r;
  Model model = model_in;
  model.kind = ModelKind::full;  // the adiabatic model has no u or f_hat dynamics: analyse the full one
  r.alpha = model.plane.inclination;
  r.spin = spin;
  r.rotor_spin = model.top.has_rotor ? rotor_spin : 0.0;
  r.slip = st.slip;
  if (!st.exists || !st.phi_defined) {
    r.reason = st.exists ? st.reason + "; the contact sits at the friction law's kink (v_t = 0), no linearisation"
                         : st.reason;
    return r;
  }
  if (st.slip <= 0.0) {
    r.reason = "the sleeping contact sticks (s* = 0: mu(0) >= tan(alpha)): v_t = 0 is the friction law's kink "
               "(the rolling mode of physics.md section 9), no slipping linearisation";
    return r;
  }
  const double speed = st.velocity.norm() + st.rolling_speed;
  if (speed < kRegularisedSpeeds * model.regularization_speed) {
    r.reason = "the sleeping speed |u*| + R |omega* x n| = " + std::to_string(speed) + " m/s is below " +
               std::to_string(kRegularisedSpeeds) + " v_eps: the friction there is the v_eps regularisation's " +
               "(s shifted by more than 1 %), not the law's; no linearisation";
    return r;
  }
  analyse_state(model, stationary_state_vector(model, st, spin, Eigen::Vector2d::Zero(), r.rotor_spin), options, r);
  return r;
}

StabilityResult sleeping_stability(const Model& model, double spin, double rotor_spin, const StabilityOptions& options) {
  return stability_at(model, stationary_state(model, spin), spin, rotor_spin, options);
}

StabilityResult stability_on_branch(const Model& model, double spin, double rotor_spin, double slip,
                                    const StabilityOptions& options) {
  const double mu = friction_coefficient(model.friction, slip);
  if (!(mu > 0.0)) {
    StabilityResult r;
    r.spin = spin;
    r.slip = slip;
    r.reason = "mu(s) = " + std::to_string(mu) + " <= 0 at s = " + std::to_string(slip) + ": no inclined balance";
    return r;
  }
  Model m = model;
  m.plane = make_plane(std::atan(mu), model.plane.gravity);
  return stability_at(m, stationary_state_on_root(m, spin, slip), spin, rotor_spin, options);
}

double watched_real(const StabilityResult& r, WatchedMode watched) {
  switch (watched) {
    case WatchedMode::any: return r.max_real;
    case WatchedMode::precession: return r.modes.precession.real();
    case WatchedMode::nutation: return r.modes.nutation.real();
  }
  return r.max_real;
}

namespace {

// The class of eigenvalue v in r (by the member with Im >= 0 of a pair).
std::string mode_of(const StabilityResult& r, Eigenvalue v) {
  const Eigenvalue upper(v.real(), std::abs(v.imag()));
  if (upper == r.modes.precession) return "precession";
  if (upper == r.modes.nutation) return "nutation";
  for (const Eigenvalue& b : r.modes.bearing)
    if (upper == b) return "bearing";
  return "friction";
}

// Bisects [a, b] where unstable(a) != unstable(b) (a point with no state counts as the stable side) to `tol`;
// returns the end on the unstable side, counting the bisections.
double bisect_edge(double a, double b, double tol, const std::function<int(double)>& state, int& count) {
  const int side_a = state(a);  // 1 unstable, 0 stable, -1 no state
  for (count = 0; std::abs(b - a) > tol && count < 200; ++count) {
    const double mid = 0.5 * (a + b);
    if (mid == a || mid == b) break;
    if ((state(mid) == 1) == (side_a == 1)) a = mid; else b = mid;
  }
  return side_a == 1 ? a : b;
}

}  // namespace

StabilityCrossing locate_stability_loss(const Model& model, double spin, double rotor_spin,
                                        const StabilityOptions& options, int scan_points) {
  StabilityCrossing c;
  const StationaryState st = stationary_state(model, spin);
  if (!st.exists) {
    c.reason = "no stable sleeping state at the starting alpha: " + st.reason;
    return c;
  }
  // The largest s with mu(s) > 0 (the paper law: 2 s_c, clamped to 1).
  double s_end = 1.0;
  while (s_end > st.slip && !(friction_coefficient(model.friction, s_end) > 0.0)) s_end -= 1e-3;
  auto state = [&](double s) {
    const StabilityResult r = stability_on_branch(model, spin, rotor_spin, s, options);
    return r.exists ? (r.max_real > 0.0 ? 1 : 0) : -1;
  };
  double prev = st.slip;
  if (state(prev) != 0) {
    c.reason = "the sleeping state at the starting alpha is not stable (or has no linearisation)";
    return c;
  }
  for (int i = 1; i <= scan_points; ++i) {
    const double s = st.slip + (s_end - st.slip) * i / scan_points;
    if (state(s) == 1) {
      const StabilityResult r = stability_on_branch(model, spin, rotor_spin, s, options);
      for (const Eigenvalue& v : r.eigenvalues)
        if (v != r.zero && v.real() == r.max_real) c.eigenvalue = v;
      c.mode = mode_of(r, c.eigenvalue);
      c.slip = bisect_edge(prev, s, 1e-13, state, c.bisections);
      c.alpha = std::atan(friction_coefficient(model.friction, c.slip));
      c.found = true;
      return c;
    }
    prev = s;
  }
  c.reason = "max Re stays < 0 for s up to " + std::to_string(s_end);
  return c;
}

namespace {

// The scan of unstable_spin_windows() over the analysis `at` of a spin.
std::vector<SpinWindow> scan_spin_windows(const std::function<StabilityResult(double)>& at, double w0, double w1,
                                          int points, WatchedMode watched) {
  std::vector<SpinWindow> windows;
  auto state = [&](double w) {
    const StabilityResult r = at(w);
    return r.exists ? (watched_real(r, watched) > 0.0 ? 1 : 0) : -1;
  };
  const double tol = 1e-12 * std::max(std::abs(w1 - w0), 1e-300);
  int count = 0, prev_state = -2;
  double prev = w0;
  for (int i = 0; i < points; ++i) {
    const double w = points == 1 ? w0 : w0 + (w1 - w0) * i / (points - 1);
    const StabilityResult r = at(w);
    const int now = r.exists ? (watched_real(r, watched) > 0.0 ? 1 : 0) : -1;
    if (now == 1 && prev_state != 1) {
      windows.push_back({prev_state == -2 ? w : bisect_edge(w, prev, tol, state, count), w1, -INFINITY, w});
    } else if (now != 1 && prev_state == 1) {
      windows.back().upper = bisect_edge(prev, w, tol, state, count);
    }
    if (now == 1 && watched_real(r, watched) > windows.back().max_real) {
      windows.back().max_real = watched_real(r, watched);
      windows.back().at_spin = w;
    }
    prev_state = now;
    prev = w;
  }
  return windows;
}

double axis_sign(SpinningState state) { return state == SpinningState::upright ? 1.0 : -1.0; }

}  // namespace

std::vector<SpinWindow> unstable_spin_windows(const Model& model, double rotor_spin, double w0, double w1, int points,
                                              WatchedMode watched, const StabilityOptions& options) {
  return scan_spin_windows([&](double w) { return sleeping_stability(model, w, rotor_spin, options); }, w0, w1,
                           points, watched);
}

std::vector<SpinWindow> unstable_spin_windows(const Model& model, SpinningState state, double rotor_spin, double w0,
                                              double w1, int points, WatchedMode watched,
                                              const StabilityOptions& options) {
  return scan_spin_windows([&](double w) { return spinning_stability(model, state, w, rotor_spin, options); }, w0,
                           w1, points, watched);
}

const char* to_string(SpinningState state) { return state == SpinningState::upright ? "upright" : "inverted"; }

bool parse_spinning_state(const std::string& name, SpinningState& out) {
  if (name != "upright" && name != "inverted") return false;
  out = name == "upright" ? SpinningState::upright : SpinningState::inverted;
  return true;
}

StateVector spinning_state(const Model& model, SpinningState state, double spin, double rotor_spin) {
  StateVector y{};
  const Eigen::Vector3d f_hat = axis_sign(state) * Eigen::Vector3d::UnitZ();
  set_figure_axis(y, f_hat);
  set_angular_velocity(y, spin * f_hat);
  y[idx::nu] = model.top.has_rotor ? rotor_spin - spin : 0.0;
  return y;
}

namespace {

// A plane without friction at any slip (coulomb mu = 0): its linearisation is exact, Maxwell-Klein's smooth plane.
bool frictionless(const FrictionLaw& law) { return law.kind == FrictionLawKind::coulomb && law.mu == 0.0; }

}  // namespace

std::string spinning_state_refusal(const Model& model, SpinningState state) {
  const std::string name = to_string(state);
  const double f = model.top.com_offset;
  if (f == 0.0)
    return "top.com_offset = 0 m: a ball's figure axis is only a marker, it has no " + name + " spinning state";
  if (f > 0.0 && state == SpinningState::inverted)
    return "top.com_offset = " + format_number(f) + " m: an ordinary top (com_offset > 0) has no inverted state " +
           "on its tip sphere (it would stand on its body); only --state upright";
  if (model.plane.inclination != 0.0)
    return "plane.inclination = " + format_number(model.plane.inclination) + " rad: the " + name +
           " spinning state is an equilibrium on a level plane only (plane.inclination 0)";
  if (state == SpinningState::inverted && std::cos(model.top.max_tilt) > -1.0 + 1e-12)
    return "top.max_tilt = " + format_number(model.top.max_tilt) + " rad: the inverted state (tilt pi) needs " +
           "max_tilt = pi (only the sphere touches the plane)";
  if (frictionless(model.friction)) return "";
  if (model.finite_contact.has_patch()) {
    // A spinning patch pivots (s = 1 at v_t = 0): F = -mu(1) N v_t / |w| is smooth there.
    const double mu1 = friction_coefficient(model.friction, 1.0);
    if (!(mu1 > 0.0))
      return "mu(1) = " + format_number(mu1) + ": a pivoting patch (s = 1) has no friction under this law, so the " +
             "linearisation is frictionless and does not decide stability (needs mu(1) > 0, or coulomb mu 0)";
    return "";
  }
  const double mu0 = friction_coefficient(model.friction, 0.0);
  if (!(mu0 > 0.0))
    return "mu(0) = " + format_number(mu0) + ": a point contact at v_t = 0 sits at the friction law's kink (no " +
           "friction at zero slip, the linearisation is frictionless and does not decide stability); needs mu(0) > 0 " +
           "(e.g. coulomb), a patch (contact.patch_radius > 0 or hertz), or a frictionless plane (coulomb mu 0)";
  return "";
}

StabilityResult spinning_stability(const Model& model_in, SpinningState state, double spin, double rotor_spin,
                                   const StabilityOptions& options) {
  StabilityResult r;
  Model model = model_in;
  model.kind = ModelKind::full;  // as stability_at
  r.alpha = model.plane.inclination;
  r.spin = spin;
  r.rotor_spin = model.top.has_rotor ? rotor_spin : 0.0;
  r.reason = spinning_state_refusal(model, state);
  if (r.reason.empty()) analyse_state(model, spinning_state(model, state, spin, r.rotor_spin), options, r);
  return r;
}

double maxwell_klein_critical_spin(const Model& model) {
  const Top& top = model.top;
  return std::sqrt(4.0 * top.inertia_transverse * top.mass * model.plane.gravity * top.com_offset) / top.inertia_axial;
}

CriticalSpin locate_critical_spin(const Model& model, SpinningState state, double rotor_spin, double w0, double w1,
                                  int points, const StabilityOptions& options) {
  CriticalSpin c;
  auto analyse = [&](double w) { return spinning_stability(model, state, w, rotor_spin, options); };
  auto side = [&](double w) {
    const StabilityResult r = analyse(w);
    return r.exists ? (r.max_real > options.stability_tolerance ? 1 : 0) : -1;
  };
  if (!(0.0 < w0 && w0 < w1) || points < 2) {
    c.reason = "the scan needs 0 < w0 < w1 and at least 2 points";
    return c;
  }
  if (const std::string why = spinning_state_refusal(model, state); !why.empty()) {
    c.reason = why;
    return c;
  }
  if (side(w1) != 0) {
    c.reason = "the state is not stable at the top of the scan, " + format_number(w1) + " rad/s";
    return c;
  }
  double prev = w1;
  for (int i = 1; i < points; ++i) {
    const double w = w1 - (w1 - w0) * i / (points - 1);
    if (side(w) == 1) {
      const StabilityResult r = analyse(w);
      for (const Eigenvalue& v : r.eigenvalues)
        if (v != r.zero && v.real() == r.max_real) c.eigenvalue = {v.real(), std::abs(v.imag())};
      c.mode = mode_of(r, c.eigenvalue);
      c.spin = bisect_edge(w, prev, 1e-12 * (w1 - w0), side, c.bisections);
      c.found = true;
      return c;
    }
    prev = w;
  }
  c.reason = "stable at every scanned spin down to " + format_number(w0) + " rad/s";
  return c;
}

namespace {

// The precession mode of the spinning state at `spin`: its eigenvalue, right eigenvector normalised to r_a = 1 (the
// tilt component along e1) and left eigenvector; false where the state cannot be analysed.
bool precession_mode(const Model& model, SpinningState state, double spin, const StabilityOptions& options,
                     Eigenvalue& lambda, Eigen::VectorXcd& right, Eigen::VectorXcd& left) {
  const StabilityResult r = spinning_stability(model, state, spin, 0.0, options);
  if (!r.exists) return false;
  auto nearest = [](const Eigen::VectorXcd& ev, Eigenvalue target) {
    Eigen::Index k = 0;
    (ev.array() - target).abs().minCoeff(&k);
    return k;
  };
  const Eigen::EigenSolver<Eigen::MatrixXd> es(r.jacobian);
  const Eigen::Index k = nearest(es.eigenvalues(), r.modes.precession);
  lambda = es.eigenvalues()[k];
  right = es.eigenvectors().col(k) / es.eigenvectors()(2, k);
  const Eigen::EigenSolver<Eigen::MatrixXd> et(r.jacobian.transpose());
  left = et.eigenvectors().col(nearest(et.eigenvalues(), lambda));
  return true;
}

}  // namespace

double passage_growth_rate(const Model& model, SpinningState state, double spin, double spin_rate,
                           const StabilityOptions& options) {
  Eigenvalue lambda, lp, lm;
  Eigen::VectorXcd r, l, rp, lpv, rm, lmv;
  const double dw = 1e-4 * std::abs(spin);  // the mode changes on the scale of the spin itself
  if (!precession_mode(model, state, spin, options, lambda, r, l) ||
      !precession_mode(model, state, spin + dw, options, lp, rp, lpv) ||
      !precession_mode(model, state, spin - dw, options, lm, rm, lmv))
    return NAN;
  const Eigen::VectorXcd dr = (rp - rm) / (2.0 * dw);
  const Eigenvalue drift = l.transpose() * dr;
  const Eigenvalue norm = l.transpose() * r;
  return lambda.real() - (drift / norm).real() * spin_rate;
}

double magnus_critical_spin_squared(const Model& model, SpinningState state) {
  const Top& top = model.top;
  const double r = top.tip_radius;
  const double a = -axis_sign(state) * top.com_offset;  // > 0: the centre of mass below the sphere's centre
  const double h = r - a;                               // the centre of mass's height above the contact
  const double I1 = top.inertia_transverse, I3 = top.inertia_axial;
  return -a * top.mass * model.plane.gravity / ((r / h) * I1 * (I3 / I1 - r / h));
}

}  // namespace top_sim
