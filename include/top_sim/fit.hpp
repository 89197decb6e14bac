// Fitting friction laws to measurements (docs/analysis.md, "Fitting friction laws"): the sleeping states'
// (alpha, phi*) pairs, or a measured contact-point path compared with simulations of a scene.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "top_sim/friction.hpp"
#include "top_sim/scene.hpp"

namespace top_sim {

// What every fit returns. Standard errors are sqrt(diag(covariance)); the covariance is (J^T J)^-1 of the
// weighted residuals at the optimum, scaled by chi2 / dof when the data gave no uncertainties (sigma_known false).
struct FitResult {
  std::vector<std::string> names;      // the fitted parameters, in order
  Eigen::VectorXd values, errors;
  Eigen::MatrixXd covariance;
  double chi2 = 0.0;                   // sum of squared weighted residuals at the optimum
  int dof = 0;                         // points - parameters
  bool sigma_known = true;             // false: errors estimated from the scatter (chi2 / dof)
  bool converged = false;
  std::string message;                 // the solver's stop reason
  int evaluations = 0;                 // residual evaluations (each a set of simulations for a trajectory fit)
  // Parameters the solver pushed past their allowed range (the simulation used the nearest allowed value): the
  // optimum lies on that bound and the errors there are not meaningful.
  std::vector<std::string> at_bound;
  double value(const std::string& name) const;  // throws std::out_of_range
  double error(const std::string& name) const;
};

// A bad data set or fit request (too few points, non-finite values, unknown parameter): the message says which.
class FitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ---- stationary fit: tan(alpha_i) = mu(s_i), s_i = tan(phi_i / 2) ----

// One measured sleeping state. sigma <= 0 or NaN: not given.
struct StationaryMeasurement {
  double alpha = 0.0, phi = 0.0;  // plane inclination, travel direction from h towards downhill [rad]
  double sigma_alpha = 0.0, sigma_phi = 0.0;
};

// A measurement mapped on mu(s), with its linearly propagated standard errors.
struct SlipPoint {
  double s = 0.0, y = 0.0;            // tan(phi'/2), tan(alpha)
  double sigma_s = 0.0, sigma_y = 0.0;
  bool mirrored = false;              // phi > pi/2 was mapped to pi - phi (negative spin, physics.md section 5)
};

// s = tan(phi'/2) with phi' = phi, or pi - phi for phi > pi/2 (the mirror rule); y = tan(alpha);
// sigma_s = sigma_phi (1 + s^2) / 2, sigma_y = sigma_alpha (1 + y^2). Unknown sigmas stay 0.
SlipPoint slip_point(const StationaryMeasurement& m);

struct StationaryFitOptions {
  FrictionLawKind law = FrictionLawKind::paper;
  // The first guess (paper: mu_c, s_c; linearized: mu0, k and the fixed s0). table: mu at table_slips, guessed
  // from the data. Defaults: FrictionLaw's.
  FrictionLaw guess;
  std::vector<double> table_slips;  // table: the fixed nodes s_j (empty: 4 evenly spread over the data's s range)
  // Used for every point when the data have no sigma columns (equal weights; errors then scaled by chi2/dof).
  double default_sigma_alpha = 1.0, default_sigma_phi = 1.0;
};

// Orthogonal-distance (errors-in-variables) fit of the law's parameters: the true slips s_i are fitted too;
// chi2 = sum ((s_i' - s_i) / sigma_s_i)^2 + ((mu(s_i') - y_i) / sigma_y_i)^2, dof = n - parameters.
// Parameters: paper mu_c, s_c; linearized mu0, k (s0 fixed at the guess's: mu0 and s0 are not separable);
// table mu@<s_j> at the fixed nodes. Throws FitError on bad data.
FitResult fit_stationary(const std::vector<StationaryMeasurement>& data, const StationaryFitOptions& options);

// The law a stationary fit found (for plotting mu(s) and for scenes).
FrictionLaw fitted_law(const FitResult& r, const StationaryFitOptions& options, const std::vector<SlipPoint>& points);

// The table nodes a fit uses: options.table_slips, or 4 evenly spread over the points' s range.
std::vector<double> table_nodes(const StationaryFitOptions& options, const std::vector<SlipPoint>& points);

// ---- trajectory fit: contact-point path against simulations of a scene ----

struct ContactSample {
  double t = 0.0, x = 0.0, y = 0.0;  // contact_x, contact_y [m] at simulated time t [s]
};

// The parameters a trajectory fit may free, named like the scene keys: friction.<name of the scene law's
// parameters> (e.g. friction.mu_c), initial.tilt, initial.spin, initial.tilt_azimuth.
std::vector<std::string> trajectory_parameter_names(const Scene& scene);

// Sets parameter `name` of the scene (throws FitError for a name not in trajectory_parameter_names).
void set_scene_parameter(Scene& scene, const std::string& name, double value);
double get_scene_parameter(const Scene& scene, const std::string& name);

struct TrajectoryFitOptions {
  // Least squares on the contact positions; sigma_position > 0: the positions' standard error [m] (absolute
  // errors); <= 0: unknown (errors from the scatter, chi2/dof).
  double sigma_position = 0.0;
  // Continuation: the fit runs on the samples with t <= f * t_last for each f in turn, each stage starting from
  // the previous one's optimum (a long window from a poor guess has many local minima).
  std::vector<double> windows = {0.125, 0.25, 0.5, 1.0};
  int max_evaluations_per_stage = 60;
};

// Fits the named scene parameters (their first guesses: the scene's values). Throws FitError on bad data or names.
FitResult fit_trajectory(const Scene& scene, const std::vector<ContactSample>& data,
                         const std::vector<std::string>& free, const TrajectoryFitOptions& options = {});

// The simulated contact positions of `scene` at the (ascending) times of `data`; after a contact fault the last
// position is held.
std::vector<ContactSample> simulate_contact(const Scene& scene, const std::vector<ContactSample>& data);

}  // namespace top_sim
