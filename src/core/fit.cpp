// Friction-law fits (docs/analysis.md, "Fitting friction laws"): Eigen's MINPACK-style Levenberg-Marquardt with
// its internal parameter scaling, central-difference Jacobians and the covariance (J^T J)^-1 at the optimum.
#include "top_sim/fit.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/NonLinearOptimization>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "top_sim/format.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/limits.hpp"

namespace top_sim {

double FitResult::value(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return values[static_cast<Eigen::Index>(i)];
  throw std::out_of_range("no fitted parameter " + name);
}

double FitResult::error(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return errors[static_cast<Eigen::Index>(i)];
  throw std::out_of_range("no fitted parameter " + name);
}

namespace {

using Residuals = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& r)>;

// The functor Eigen's LevenbergMarquardt drives: residuals and their central-difference Jacobian.
struct LeastSquares {
  using Scalar = double;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;

  int n = 0, m = 0;
  Residuals residuals;
  Eigen::VectorXd steps;  // finite-difference step per parameter
  int* evaluations = nullptr;

  int inputs() const { return n; }
  int values() const { return m; }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
    residuals(x, r);
    ++*evaluations;
    return 0;
  }
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& jac) const {
    Eigen::VectorXd xp = x, rp(m), rm(m);
    for (int j = 0; j < n; ++j) {
      const double h = steps[j];
      xp[j] = x[j] + h;
      residuals(xp, rp);
      xp[j] = x[j] - h;
      residuals(xp, rm);
      xp[j] = x[j];
      jac.col(j) = (rp - rm) / (2.0 * h);
      *evaluations += 2;
    }
    return 0;
  }
};

const char* lm_message(int status) {
  switch (status) {
    case 1: return "relative reduction of chi2 below ftol";
    case 2: return "relative change of the parameters below xtol";
    case 3: return "chi2 and parameters converged";
    case 4: return "residuals orthogonal to the Jacobian";
    case 5: return "too many evaluations";
    case 6: return "ftol too small: no further reduction possible";
    case 7: return "xtol too small: no further improvement possible";
    case 8: return "gtol too small: residuals orthogonal to the Jacobian";
    default: return "improper input to the solver";
  }
}

struct LmOutcome {
  int status = 0;
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
};

// Minimises |r(x)|^2 from x (updated in place); returns the stop status, the residuals and Jacobian at x.
LmOutcome minimise(LeastSquares& f, Eigen::VectorXd& x, int max_evaluations, double factor) {
  Eigen::LevenbergMarquardt<LeastSquares> lm(f);
  lm.parameters.maxfev = max_evaluations;
  lm.parameters.factor = factor;
  LmOutcome out;
  out.status = static_cast<int>(lm.minimize(x));
  out.r.resize(f.m);
  f(x, out.r);
  out.jac.resize(f.m, f.n);
  f.df(x, out.jac);
  return out;
}

// Covariance of the first p parameters, (J^T J)^-1 (pseudo-inverse when singular), scaled when sigma is unknown.
void fill_errors(const LmOutcome& o, int p, FitResult& res) {
  const Eigen::MatrixXd jtj = o.jac.transpose() * o.jac;
  const Eigen::MatrixXd inv = jtj.completeOrthogonalDecomposition().pseudoInverse();
  res.chi2 = o.r.squaredNorm();
  res.covariance = inv.topLeftCorner(p, p);
  if (!res.sigma_known && res.dof > 0) res.covariance *= res.chi2 / res.dof;
  res.errors = res.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  res.converged = o.status >= 1 && o.status <= 8 && o.status != 5;
  res.message = lm_message(o.status);
}

void require_finite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw FitError(what + " = " + format_number(v) + ": must be a finite number");
}

// ---- stationary ----

struct LawModel {
  FrictionLaw law;
  std::vector<std::string> names;
  std::vector<double> nodes;  // table
};

LawModel law_model(const StationaryFitOptions& o, const std::vector<SlipPoint>& points) {
  LawModel m;
  m.law = o.guess;
  m.law.kind = o.law;
  switch (o.law) {
    case FrictionLawKind::paper: m.names = {"mu_c", "s_c"}; break;
    case FrictionLawKind::linearized: m.names = {"mu0", "k"}; break;
    case FrictionLawKind::table:
      m.nodes = table_nodes(o, points);
      for (double s : m.nodes) m.names.push_back("mu@" + format_number(s));
      break;
    default: throw FitError(std::string("law ") + to_string(o.law) + " cannot be fitted: use paper, linearized or table");
  }
  return m;
}

// The law with parameters beta.
FrictionLaw with_parameters(const LawModel& m, const Eigen::VectorXd& beta) {
  FrictionLaw law = m.law;
  switch (law.kind) {
    case FrictionLawKind::paper: law.mu_c = beta[0]; law.s_c = beta[1]; break;
    case FrictionLawKind::linearized: law.mu0 = beta[0]; law.k = beta[1]; break;
    default:
      law.points.clear();
      for (std::size_t j = 0; j < m.nodes.size(); ++j) law.points.emplace_back(m.nodes[j], beta[static_cast<Eigen::Index>(j)]);
  }
  return law;
}

std::vector<SlipPoint> slip_points(const std::vector<StationaryMeasurement>& data, const StationaryFitOptions& o,
                                   bool& sigma_known) {
  std::size_t with_sigma = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const auto& d = data[i];
    const std::string row = "point " + std::to_string(i + 1);
    require_finite(d.alpha, row + ": alpha");
    require_finite(d.phi, row + ": phi");
    const bool given = d.sigma_alpha > 0.0 || d.sigma_phi > 0.0;
    if (given && !(d.sigma_alpha > 0.0 && d.sigma_phi > 0.0 && std::isfinite(d.sigma_alpha) && std::isfinite(d.sigma_phi)))
      throw FitError(row + ": sigma_alpha and sigma_phi must both be finite and > 0");
    // phi slightly below 0 is a noisy measurement near alpha = 0 (s < 0 is fitted as it is).
    if (!admissible_inclination(d.alpha) || !(d.phi > -M_PI_2 && d.phi <= M_PI))
      throw FitError(row + ": alpha must be in (-pi/2, pi/2) and phi in (-pi/2, pi]");
    with_sigma += given;
  }
  if (with_sigma != 0 && with_sigma != data.size())
    throw FitError("sigma_alpha, sigma_phi given for some points only: give them for every point or none");
  sigma_known = with_sigma != 0;
  std::vector<SlipPoint> pts;
  for (const auto& d : data) {
    StationaryMeasurement m = d;
    if (!sigma_known) m.sigma_alpha = o.default_sigma_alpha, m.sigma_phi = o.default_sigma_phi;
    pts.push_back(slip_point(m));
  }
  return pts;
}

}  // namespace

SlipPoint slip_point(const StationaryMeasurement& m) {
  SlipPoint p;
  p.mirrored = m.phi > M_PI_2;
  const double phi = p.mirrored ? M_PI - m.phi : m.phi;
  p.s = std::tan(0.5 * phi);
  p.y = std::tan(m.alpha);
  p.sigma_s = m.sigma_phi > 0.0 ? m.sigma_phi * 0.5 * (1.0 + p.s * p.s) : 0.0;
  p.sigma_y = m.sigma_alpha > 0.0 ? m.sigma_alpha * (1.0 + p.y * p.y) : 0.0;
  return p;
}

std::vector<double> table_nodes(const StationaryFitOptions& o, const std::vector<SlipPoint>& points) {
  if (!o.table_slips.empty()) {
    for (std::size_t j = 0; j < o.table_slips.size(); ++j)
      if (!(o.table_slips[j] >= 0.0 && o.table_slips[j] <= 1.0) || (j > 0 && o.table_slips[j] <= o.table_slips[j - 1]))
        throw FitError("table slips must be strictly increasing in [0, 1]");
    if (o.table_slips.size() < 2) throw FitError("table slips: need at least 2");
    return o.table_slips;
  }
  double lo = 1.0, hi = 0.0;
  for (const auto& p : points) lo = std::min(lo, p.s), hi = std::max(hi, p.s);
  if (!(hi > lo)) throw FitError("table law: the points span no range of s; give the nodes");
  std::vector<double> nodes;
  for (int j = 0; j < 4; ++j) nodes.push_back(lo + (hi - lo) * j / 3.0);
  return nodes;
}

FitResult fit_stationary(const std::vector<StationaryMeasurement>& data, const StationaryFitOptions& options) {
  FitResult res;
  const std::vector<SlipPoint> pts = slip_points(data, options, res.sigma_known);
  const LawModel model = law_model(options, pts);
  const int p = static_cast<int>(model.names.size()), n = static_cast<int>(pts.size());
  if (n < p)
    throw FitError(std::to_string(n) + (n == 1 ? " point is" : " points are") + " fewer than the " +
                   std::to_string(p) + " parameters");
  if (n == p && !res.sigma_known) throw FitError("without sigma columns the errors need more points than parameters");
  res.names = model.names;
  res.dof = n - p;

  Eigen::VectorXd x(p + n);  // [law parameters, true slips]
  if (options.law == FrictionLawKind::paper) x.head(2) << model.law.mu_c, model.law.s_c;
  else if (options.law == FrictionLawKind::linearized) x.head(2) << model.law.mu0, model.law.k;
  else {
    double mean = 0.0;
    for (const auto& q : pts) mean += q.y / n;
    x.head(p).setConstant(mean);
  }
  for (int i = 0; i < n; ++i) x[p + i] = pts[static_cast<std::size_t>(i)].s;

  LeastSquares f;
  f.n = p + n;
  f.m = 2 * n;
  f.evaluations = &res.evaluations;
  f.steps = (x.cwiseAbs().array().max(1e-2) * 1e-6).matrix();
  f.residuals = [&](const Eigen::VectorXd& xv, Eigen::VectorXd& r) {
    const FrictionLaw law = with_parameters(model, xv.head(p));
    for (int i = 0; i < n; ++i) {
      const SlipPoint& q = pts[static_cast<std::size_t>(i)];
      const double s = xv[p + i];
      r[2 * i] = (s - q.s) / q.sigma_s;
      r[2 * i + 1] = (raw_friction_coefficient(law, s) - q.y) / q.sigma_y;
    }
  };
  const LmOutcome o = minimise(f, x, 400 * (p + n + 1), 100.0);
  res.values = x.head(p);
  fill_errors(o, p, res);
  return res;
}

FrictionLaw fitted_law(const FitResult& r, const StationaryFitOptions& options, const std::vector<SlipPoint>& points) {
  LawModel m = law_model(options, points);
  return with_parameters(m, r.values);
}

// ---- trajectory ----

std::vector<std::string> trajectory_parameter_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const auto& fp : kFrictionParameters)
    if (fp.law == scene.model.friction.kind) names.push_back(std::string("friction.") + fp.name);
  for (const char* k : {"initial.tilt", "initial.spin", "initial.tilt_azimuth"}) names.push_back(k);
  return names;
}

namespace {

const FrictionParameter* friction_parameter_of(const Scene& scene, const std::string& name) {
  if (name.rfind("friction.", 0) != 0) return nullptr;
  const FrictionParameter* fp = find_friction_parameter(name.substr(9));
  return fp && fp->law == scene.model.friction.kind ? fp : nullptr;
}

double* initial_parameter(InitialConditions& ic, const std::string& name) {
  if (name == "initial.tilt") return &ic.tilt;
  if (name == "initial.spin") return &ic.spin;
  if (name == "initial.tilt_azimuth") return &ic.tilt_azimuth;
  return nullptr;
}

std::string unknown_parameter(const Scene& scene, const std::string& name) {
  std::string all;
  for (const auto& n : trajectory_parameter_names(scene)) all += (all.empty() ? "" : ", ") + n;
  return "unknown parameter '" + name + "' for this scene (friction law " + to_string(scene.model.friction.kind) +
         "); can fit: " + all;
}

// Nearest admissible value (open bounds moved inside by 1e-9 relative): the solver's trial steps may leave them.
double admissible(const ParameterRange& r, double v) {
  const double lo = r.lower_open ? r.lower + 1e-9 * std::max(1.0, std::abs(r.lower)) : r.lower;
  const double hi = r.upper_open ? r.upper - 1e-9 * std::max(1.0, std::abs(r.upper)) : r.upper;
  return std::min(std::max(v, lo), hi);
}

}  // namespace

void set_scene_parameter(Scene& scene, const std::string& name, double value) {
  if (const FrictionParameter* fp = friction_parameter_of(scene, name)) {
    scene.model.friction.*(fp->member) = admissible(fp->range, value);
  } else if (double* v = initial_parameter(scene.initial, name)) {
    *v = value;
  } else {
    throw FitError(unknown_parameter(scene, name));
  }
}

double get_scene_parameter(const Scene& scene, const std::string& name) {
  if (const FrictionParameter* fp = friction_parameter_of(scene, name)) return scene.model.friction.*(fp->member);
  InitialConditions ic = scene.initial;
  if (double* v = initial_parameter(ic, name)) return *v;
  throw FitError(unknown_parameter(scene, name));
}

std::vector<ContactSample> simulate_contact(const Scene& scene, const std::vector<ContactSample>& data) {
  Simulator sim(scene);
  std::vector<ContactSample> out;
  out.reserve(data.size());
  for (const auto& d : data) {
    if (d.t > sim.time() && sim.fault() == ContactFault::none) sim.advance_to(d.t);
    const Snapshot s = sim.snapshot();
    out.push_back({d.t, s.contact_point.x(), s.contact_point.y()});
  }
  return out;
}

namespace {

void check_trajectory_data(const std::vector<ContactSample>& data, std::size_t p) {
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::string row = "sample " + std::to_string(i + 1);
    require_finite(data[i].t, row + ": t");
    require_finite(data[i].x, row + ": contact_x");
    require_finite(data[i].y, row + ": contact_y");
    if (data[i].t < 0.0) throw FitError(row + ": t = " + format_number(data[i].t) + " < 0");
  }
  if (2 * data.size() < p + 1)
    throw FitError(std::to_string(data.size()) + " samples (" + std::to_string(2 * data.size()) +
                   " coordinates) are too few for " + std::to_string(p) + " parameters");
}

// One continuation stage: LM on the samples `window` from x (updated).
LmOutcome trajectory_stage(const Scene& scene, const std::vector<ContactSample>& window,
                           const std::vector<std::string>& free, double sigma, Eigen::VectorXd& x,
                           int max_evaluations, int& evaluations) {
  const int p = static_cast<int>(free.size()), m = static_cast<int>(2 * window.size());
  LeastSquares f;
  f.n = p;
  f.m = m;
  f.evaluations = &evaluations;
  f.steps = (x.cwiseAbs().array().max(1e-3) * 1e-4).matrix();
  f.residuals = [&](const Eigen::VectorXd& xv, Eigen::VectorXd& r) {
    Scene trial = scene;
    for (int j = 0; j < p; ++j) set_scene_parameter(trial, free[static_cast<std::size_t>(j)], xv[j]);
    const std::vector<ContactSample> sim = simulate_contact(trial, window);
    for (std::size_t k = 0; k < window.size(); ++k) {
      r[static_cast<Eigen::Index>(2 * k)] = (sim[k].x - window[k].x) / sigma;
      r[static_cast<Eigen::Index>(2 * k + 1)] = (sim[k].y - window[k].y) / sigma;
    }
  };
  return minimise(f, x, max_evaluations, 1.0);
}

}  // namespace

FitResult fit_trajectory(const Scene& scene, const std::vector<ContactSample>& data_in,
                         const std::vector<std::string>& free, const TrajectoryFitOptions& options) {
  if (free.empty()) throw FitError("no free parameters given");
  for (std::size_t j = 0; j < free.size(); ++j)
    for (std::size_t k = 0; k < j; ++k)
      if (free[j] == free[k]) throw FitError("parameter '" + free[j] + "' named twice");
  std::vector<ContactSample> data = data_in;
  check_trajectory_data(data, free.size());
  std::stable_sort(data.begin(), data.end(), [](const auto& a, const auto& b) { return a.t < b.t; });

  FitResult res;
  res.names = free;
  res.sigma_known = options.sigma_position > 0.0;
  const double sigma = res.sigma_known ? options.sigma_position : 1e-6;  // unknown: any scale, errors from chi2/dof
  const int p = static_cast<int>(free.size());
  Eigen::VectorXd x(p);
  for (int j = 0; j < p; ++j) x[j] = get_scene_parameter(scene, free[static_cast<std::size_t>(j)]);

  LmOutcome o;
  std::size_t used = 0;
  for (double fraction : options.windows) {
    const double t_end = fraction * data.back().t;
    std::vector<ContactSample> window;
    for (const auto& d : data)
      if (d.t <= t_end * (1.0 + 1e-12)) window.push_back(d);
    if (static_cast<int>(2 * window.size()) <= p || window.size() == used) continue;  // too short or no new data
    used = window.size();
    o = trajectory_stage(scene, window, free, sigma, x, options.max_evaluations_per_stage, res.evaluations);
  }
  if (used != data.size())  // the windows did not end with every sample: one last stage on all of them
    o = trajectory_stage(scene, data, free, sigma, x, options.max_evaluations_per_stage, res.evaluations);
  res.dof = static_cast<int>(2 * data.size()) - p;
  res.values = x;
  fill_errors(o, p, res);
  for (int j = 0; j < p; ++j) {  // report the value the simulation used (the solver may have left a bound)
    Scene s = scene;
    set_scene_parameter(s, free[static_cast<std::size_t>(j)], x[j]);
    res.values[j] = get_scene_parameter(s, free[static_cast<std::size_t>(j)]);
    if (res.values[j] != x[j]) res.at_bound.push_back(free[static_cast<std::size_t>(j)]);
  }
  return res;
}

}  // namespace top_sim
