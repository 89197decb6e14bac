// Linear stability of the sleeping state (physics.md section 10): the Jacobian of the right-hand side at the
// analytic sleeping state of section 5, by central finite differences of the core's own right-hand side, its
// eigenvalues and their classification; the loss of stability along the slip branch (alpha_c) and the unstable
// windows of a spin sweep. docs/analysis.md has the method, the step choice and the measured figures.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "top_sim/model.hpp"
#include "top_sim/state.hpp"
#include "top_sim/stationary.hpp"

namespace top_sim {

using Eigenvalue = std::complex<double>;

// The reduced coordinates of section 10, in this order: u (2, in-plane velocity of the tip-sphere centre), the
// figure axis on its tangent plane at f_hat* (2: a = e1 . f_hat, b = e2 . f_hat with e1, e2, f_hat* orthonormal,
// f_hat = a e1 + b e2 + sqrt(1 - a^2 - b^2) f_hat*), omega (3, shell angular velocity), and nu (1, rotor spin
// relative to the shell) for a gyroscope-loaded top. p, W_diss, psi (and the gap, 0 in contact) do not feed back.
struct ReducedCoordinates {
  Eigen::Vector3d f_star = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
  bool rotor = false;
  int size() const { return rotor ? 8 : 7; }
};

// Tangent basis at f_star (any orthonormal pair: the eigenvalues do not depend on it).
ReducedCoordinates reduced_coordinates(const Model& model, const Eigen::Vector3d& f_star);
// The full state at reduced coordinates z (position, W_diss, gap, gap rate and psi zero).
StateVector expand(const ReducedCoordinates& rc, const Eigen::VectorXd& z);
// The reduced coordinates of a state, and the reduced rate of a full rate dy/dt (a' = e1 . f_hat', ...).
Eigen::VectorXd reduce(const ReducedCoordinates& rc, const StateVector& y);
Eigen::VectorXd reduce_rate(const ReducedCoordinates& rc, const StateVector& dydt);

// Finite differences. Column j of the Jacobian is (F(z + h_j e_j) - F(z - h_j e_j)) / (2 h_j), h_j = step *
// scale_j, where scale_j is the width over which the right-hand side changes along coordinate j: |v_t*| for u
// (the slip s = |v_t| / (|u| + R |omega x n| + v_eps) and the friction direction turn on that scale),
// min(|v_t*| / R, |omega*|) for omega (v_t = u - R omega x n), 1 rad for the figure axis, max(|omega*|, |Omega|)
// for nu. step = cbrt(machine epsilon) balances the O(h^2) truncation error of a central difference against its
// O(eps / h) rounding error. With richardson, J = (4 J(h/2) - J(h)) / 3 (cancels the h^2 term; the same to
// 1e-9 1/s here, docs/analysis.md).
struct StabilityOptions {
  double step = 6.0554544523933395e-06;  // cbrt(2^-52)
  bool richardson = false;
  // Stable when every eigenvalue but the zero one has Re < -stability_tolerance [1/s]: about 100 times the
  // finite-difference error of the slow eigenvalues (1e-9 1/s at 200 rad/s, docs/analysis.md).
  double stability_tolerance = 1e-7;
};

// J = dF/dz of the reduced right-hand side at the state y (slipping contact, the model's normal force).
Eigen::MatrixXd reduced_jacobian(const Model& model, const StateVector& y, const StabilityOptions& options = {});

// The classified spectrum (physics.md section 10). Pairs are given by their member with Im >= 0.
struct StabilityModes {
  Eigenvalue precession{0.0, 0.0};   // slow precession, the pair nearest i m g f / |L_total . f_hat|
  Eigenvalue nutation{0.0, 0.0};     // fast nutation, the pair nearest i |L_total . f_hat| / I_d
  std::vector<Eigenvalue> friction;  // the others (fast friction modes), both members of a pair, decreasing Re
  std::vector<Eigenvalue> bearing;   // gyroscope-loaded top: the real eigenvalue nearest -c (1/J + 1/I_f')
};

struct StabilityResult {
  bool exists = false;
  std::string reason;                   // why there is no analysis, when !exists
  double alpha = 0.0, spin = 0.0;       // inclination [rad], shell spin omega* [rad/s]
  double rotor_spin = 0.0;              // absolute rotor spin Omega [rad/s] (0 without a rotor)
  double slip = 0.0;                    // s of the analysed state
  std::vector<Eigenvalue> eigenvalues;  // all, in decreasing real part
  Eigenvalue zero{0.0, 0.0};            // the eigenvalue of smallest modulus: the free spin magnitude
  StabilityModes modes;
  double max_real = 0.0;                // largest Re over every eigenvalue but the zero one [1/s]
  bool stable = false;                  // max_real < -stability_tolerance
  // 1 / |Re precession| [s]: the e-folding time of the precession (a growth time when Re > 0).
  double relaxation_time = std::numeric_limits<double>::infinity();
  // |Re precession(h) - Re precession(2 h)|: the finite-difference error estimate of Re precession [1/s];
  // resolved = it is below 1 % of |Re precession| (fails above ~1e5 rad/s: the precession rate ~ 1/omega then
  // lies below double precision relative to the Jacobian's largest entries ~ omega^2).
  double precession_error = 0.0;
  bool resolved = false;
  double residual = 0.0;                // |F(z*)|: 0 at an equilibrium; a rotor with nu != 0 drags the spin
  Eigen::MatrixXd jacobian;
};

// Stability of the sleeping state of section 5 at shell spin `spin` (the stable slip root). A gyroscope-loaded
// top has its rotor at absolute spin `rotor_spin`; with nu = rotor_spin - spin != 0 the bearing drags the shell
// spin, and the spectrum is that of the frozen state (residual > 0). No analysis (exists = false) where no
// sleeping state exists or where it does not move (alpha = 0, spin = 0, R = 0: the contact then sits at the
// friction law's kink v_t = 0), nor where it sticks (s* = 0, a law with mu(0) >= tan(alpha)), nor where its speed |u*| + R |omega* x n| is below 100 v_eps (there the v_eps
// regularisation, not the law, sets the friction: s is shifted by more than 1 %).
StabilityResult sleeping_stability(const Model& model, double spin, double rotor_spin = 0.0,
                                   const StabilityOptions& options = {});

// The same at a given stationary state (e.g. from stationary_state_on_root()).
StabilityResult stability_at(const Model& model, const StationaryState& st, double spin, double rotor_spin = 0.0,
                             const StabilityOptions& options = {});

// The sleeping state with slip `slip` on the branch mu(s) = tan(alpha): the plane is set to alpha = atan(mu(slip))
// (exists = false where mu(slip) <= 0). Both roots of the paper law are on this branch: s < s_c below s_c's
// alpha_c = atan(mu_c), s > s_c back down.
StabilityResult stability_on_branch(const Model& model, double spin, double rotor_spin, double slip,
                                    const StabilityOptions& options = {});

// Where stability is lost along the slip branch: the first sign change of max_real for s rising from the stable
// root at the model's alpha (scanned on `scan_points` slips up to the largest s with mu(s) > 0, then bisected to
// 1e-13 in s). Bisection in s, not alpha: alpha(s) = atan(mu(s)) turns back at the fold, so along alpha the
// stable branch simply ends at alpha_c.
struct StabilityCrossing {
  bool found = false;
  std::string reason;       // why not, when !found
  double slip = 0.0;        // s at the crossing
  double alpha = 0.0;       // atan(mu(s)) there: the located alpha_c
  Eigenvalue eigenvalue;    // the eigenvalue that has crossed, at the first unstable scan point
  std::string mode;         // its class: "precession", "nutation", "friction", "bearing"
  int bisections = 0;
};
StabilityCrossing locate_stability_loss(const Model& model, double spin, double rotor_spin = 0.0,
                                        const StabilityOptions& options = {}, int scan_points = 64);

// A tippe top's (com_offset f < 0: the centre of mass |f| below the sphere's centre along -f_hat) spinning states
// on a level plane (physics.md section 11, docs/analysis.md "The tippe top's spinning states"): upright = f_hat = +n
// (the centre of mass below the sphere's centre, the stem up: Magnus' a = |f| > 0), inverted = f_hat = -n (the
// centre of mass above the centre, spinning on the stem side: a = -|f|). Both spin at omega = spin f_hat (spin
// about the figure axis, as for the sleeping state; about the vertical it is +-spin) with u = 0, so the contact's
// material velocity v_t = u - R omega x n is 0: an equilibrium of the slipping model, whose regularised friction
// -mu(0) N v_t / v_eps is linear in v_t there.
enum class SpinningState { upright, inverted };
const char* to_string(SpinningState state);
bool parse_spinning_state(const std::string& name, SpinningState& out);

// The full state (position, W_diss, gap and psi zero); a rotor at absolute spin rotor_spin (nu = rotor_spin - spin).
StateVector spinning_state(const Model& model, SpinningState state, double spin, double rotor_spin = 0.0);

// Why the state cannot be analysed ("" when it can): com_offset >= 0, an inclined plane, an inverted state beyond
// the body's max_tilt (< pi), or a law with mu(0) = 0 (no friction at zero slip: the linearisation is frictionless
// and does not decide stability). Each reason names the field, its value and what is needed.
std::string spinning_state_refusal(const Model& model, SpinningState state);

// The spectrum at spinning_state() (exists = false with the refusal as reason); alpha = 0, slip = 0.
StabilityResult spinning_stability(const Model& model, SpinningState state, double spin, double rotor_spin = 0.0,
                                   const StabilityOptions& options = {});

// Magnus' critical spin squared for a friction linear in the slip velocity (Leine & Glocker, DETC2003/VIB-48426,
// Eq. 18; derived in docs/analysis.md): omega_k^2 = -a m g / ((r/h) I1 (I3/I1 - r/h)), r = R, a = -f (upright) or
// f (inverted), h = r - a, I1 = I_d, I3 = I_f. The state is stable exactly where c omega^2 < m g a with
// c = (r/h) (I1 r/h - I3): omega_k^2 < 0 means no crossing (stable at every spin when a > 0, unstable when a < 0).
double magnus_critical_spin_squared(const Model& model, SpinningState state);

// An ordinary top's (com_offset f > 0) upright state on a level plane, docs/analysis.md "The wake-up": the
// frictionless plane's (Maxwell-Klein) sleeping limit for a tip sphere, I_f^2 omega^2 > 4 I_d m g f (the smooth
// plane's normal force acts through the sphere's centre, at lever f from the centre of mass, not f + R).
double maxwell_klein_critical_spin(const Model& model);

// Where the largest real part but the zero one of a spinning state crosses stability_tolerance, scanning `points`
// spins from w1 down to w0 (0 < w0 < w1): the first unstable scan point below a stable one, bisected to 1e-12 of
// the span. An ordinary top sleeps above it (found = false with the reason when the scan has no such crossing).
struct CriticalSpin {
  bool found = false;
  std::string reason;
  double spin = 0.0;       // the crossing [rad/s]
  Eigenvalue eigenvalue;   // the eigenvalue of largest Re at the first unstable scan point, Im >= 0
  std::string mode;        // its class: "precession", "nutation", "friction"
  int bisections = 0;
};
CriticalSpin locate_critical_spin(const Model& model, SpinningState state, double rotor_spin, double w0, double w1,
                                  int points, const StabilityOptions& options = {});

// The growth rate d ln(tilt)/dt of a spinning state's precession mode while its spin changes at spin_rate [rad/s^2]
// (a slow passage, docs/analysis.md "The wake-up"): Re lambda of the frozen Jacobian plus the rate at which the
// mode's eigenvector changes along the spin, -Re(l . dr/dW / (l . r)) spin_rate, with r normalised to a unit tilt
// component (left and right eigenvectors l, r; dr/dW by a central difference of relative step 1e-4). NaN where the
// state cannot be analysed.
double passage_growth_rate(const Model& model, SpinningState state, double spin, double spin_rate,
                           const StabilityOptions& options = {});

// Which real part a spin sweep watches.
enum class WatchedMode { any, precession, nutation };

// An interval of shell spin where the watched real part is > 0. Each edge is bisected (to 1e-12 relative to the
// sweep's span) between an unstable state and a stable one, or a spin with no sleeping state (e.g. spin 0).
struct SpinWindow {
  double lower = 0.0, upper = 0.0;
  double max_real = 0.0, at_spin = 0.0;  // the largest watched Re seen on the scan inside, and where
};
// Scans `points` shell spins evenly from w0 to w1 at the model's alpha, rotor at absolute spin `rotor_spin`.
std::vector<SpinWindow> unstable_spin_windows(const Model& model, double rotor_spin, double w0, double w1, int points,
                                              WatchedMode watched, const StabilityOptions& options = {});
// The same for a tippe top's spinning state (a state that cannot be analysed counts as the stable side).
std::vector<SpinWindow> unstable_spin_windows(const Model& model, SpinningState state, double rotor_spin, double w0,
                                              double w1, int points, WatchedMode watched,
                                              const StabilityOptions& options = {});

// The watched real part of a result (max_real, Re precession or Re nutation).
double watched_real(const StabilityResult& r, WatchedMode watched);

}  // namespace top_sim
