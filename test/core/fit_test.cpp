// Friction-law fits (docs/analysis.md, "Fitting friction laws"): the stationary errors-in-variables fit and its
// error coverage, the mirror rule, the trajectory fit from a poor first guess, and top_sim_fit's data errors.
// Boost 1.74's property_tree pulls in boost/bind.hpp, which otherwise warns about its global placeholders.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#include <gtest/gtest.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "../../src/studies/fit_data.hpp"
#include "cli_util.hpp"
#include "test_util.hpp"
#include "top_sim/fit.hpp"

namespace {

using namespace top_sim;

double paper_mu(double s, double mu_c, double s_c) { return mu_c * s * (2.0 * s_c - s) / (s_c * s_c); }

// n sleeping states of the paper law (mu_c, s_c) on the stable branch, with Gaussian noise on alpha and phi.
std::vector<StationaryMeasurement> paper_data(unsigned seed, int n, double mu_c, double s_c, double sigma_alpha,
                                              double sigma_phi, bool negative_spin = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<StationaryMeasurement> data;
  for (int i = 0; i < n; ++i) {
    const double s = 0.03 + (0.9 * s_c - 0.03) * i / (n - 1);
    const double phi = 2.0 * std::atan(s);
    StationaryMeasurement m;
    m.alpha = std::atan(paper_mu(s, mu_c, s_c)) + sigma_alpha * gauss(rng);
    m.phi = (negative_spin ? M_PI - phi : phi) + sigma_phi * gauss(rng);
    m.sigma_alpha = sigma_alpha;
    m.sigma_phi = sigma_phi;
    data.push_back(m);
  }
  return data;
}

TEST(StationaryFit, TwoSigmaCoverageOverFiftySeeds) {
  const double mu_c = 0.3, s_c = 0.5;
  int covered = 0, intervals = 0, converged = 0;
  const std::clock_t c0 = std::clock();
  for (unsigned seed = 1; seed <= 50; ++seed) {
    const FitResult r = fit_stationary(paper_data(seed, 20, mu_c, s_c, 0.002, 0.01), StationaryFitOptions{});
    converged += r.converged;
    covered += std::abs(r.value("mu_c") - mu_c) <= 2.0 * r.error("mu_c");
    covered += std::abs(r.value("s_c") - s_c) <= 2.0 * r.error("s_c");
    intervals += 2;
    EXPECT_EQ(r.dof, 18);
  }
  const double coverage = static_cast<double>(covered) / intervals;
  top_sim_test::note("stationary fit: 2-sigma coverage over 50 seeds x 2 parameters", coverage);
  top_sim_test::note("stationary fit: CPU per fit of 20 points [s]",
                     static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / 50.0);
  EXPECT_EQ(converged, 50);
  EXPECT_GE(coverage, 0.90);
  EXPECT_LE(coverage, 0.99);
}

TEST(StationaryFit, MirrorRuleMapsNegativeSpinOntoTheSameLaw) {
  const auto positive = paper_data(7, 15, 0.3, 0.5, 0.002, 0.01);
  const auto negative = paper_data(7, 15, 0.3, 0.5, 0.002, 0.01, true);
  const SlipPoint p = slip_point(positive[3]), q = slip_point(negative[3]);
  EXPECT_FALSE(p.mirrored);
  EXPECT_TRUE(q.mirrored);
  const FitResult a = fit_stationary(positive, {}), b = fit_stationary(negative, {});
  // Same true slips, independent noise draws mirrored: both estimates agree with the truth and each other.
  EXPECT_NEAR(a.value("mu_c"), 0.3, 3.0 * a.error("mu_c"));
  EXPECT_NEAR(b.value("mu_c"), 0.3, 3.0 * b.error("mu_c"));
  EXPECT_NEAR(b.value("s_c"), 0.5, 3.0 * b.error("s_c"));
  // Exactly mirrored data (phi -> pi - phi of the same numbers) give the same fit.
  auto mirrored = positive;
  for (auto& m : mirrored) m.phi = M_PI - m.phi;
  const FitResult c = fit_stationary(mirrored, {});
  EXPECT_NEAR(c.value("mu_c"), a.value("mu_c"), 1e-9);
  EXPECT_NEAR(c.value("s_c"), a.value("s_c"), 1e-9);
}

TEST(StationaryFit, LinearizedAndTableLawsRecoverExactData) {
  std::vector<StationaryMeasurement> data;
  for (int i = 0; i < 8; ++i) {
    const double s = 0.05 + 0.05 * i;
    data.push_back({std::atan(0.12 + 0.8 * (s - 0.3)), 2.0 * std::atan(s), 1e-3, 1e-3});
  }
  StationaryFitOptions lin;
  lin.law = FrictionLawKind::linearized;
  const FitResult r = fit_stationary(data, lin);
  EXPECT_EQ(r.names, (std::vector<std::string>{"mu0", "k"}));
  EXPECT_NEAR(r.value("mu0"), 0.12, 1e-7);
  EXPECT_NEAR(r.value("k"), 0.8, 1e-6);
  StationaryFitOptions table;
  table.law = FrictionLawKind::table;
  table.table_slips = {0.05, 0.2, 0.4};
  const FitResult t = fit_stationary(data, table);
  ASSERT_EQ(t.names.size(), 3u);
  EXPECT_EQ(t.names[1], "mu@0.2");
  EXPECT_NEAR(t.values[1], 0.12 + 0.8 * (0.2 - 0.3), 1e-7);
}

TEST(StationaryFit, BadDataThrowsWithTheReason) {
  auto data = paper_data(1, 5, 0.3, 0.5, 0.002, 0.01);
  std::vector<StationaryMeasurement> one(data.begin(), data.begin() + 1);
  EXPECT_THROW(fit_stationary(one, {}), FitError);
  data[2].phi = std::nan("");
  try {
    fit_stationary(data, {});
    FAIL() << "no error";
  } catch (const FitError& e) {
    EXPECT_NE(std::string(e.what()).find("point 3: phi"), std::string::npos) << e.what();
  }
}

TEST(TrajectoryFit, RecoversPaperParametersFromTheDefaultsWithinOnePercent) {
  const std::string yaml = "top: aluminium\nplane: {inclination: 0.1}\n"
                           "friction: {law: paper, mu_c: 0.31, s_c: 0.52}\n"
                           "initial: {start: tilted, tilt: 0.1, spin: 200.0}\n";
  const Scene truth = top_sim_test::scene_from(yaml);
  std::vector<ContactSample> times;
  for (int k = 1; k <= 200; ++k) times.push_back({0.01 * k, 0.0, 0.0});
  std::vector<ContactSample> data = simulate_contact(truth, times);
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 1e-6);
  for (auto& d : data) d.x += noise(rng), d.y += noise(rng);

  Scene guess = truth;
  guess.model.friction = FrictionLaw{};  // the paper law with its defaults: mu_c 0.25, s_c 0.6
  TrajectoryFitOptions opt;
  opt.sigma_position = 1e-6;
  const std::clock_t c0 = std::clock();
  const FitResult r = fit_trajectory(guess, data, {"friction.mu_c", "friction.s_c"}, opt);
  top_sim_test::note("trajectory fit CPU [s]", static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
  top_sim_test::note("trajectory fit evaluations", r.evaluations);
  top_sim_test::note("trajectory fit mu_c", r.value("friction.mu_c"));
  top_sim_test::note("trajectory fit mu_c error", r.error("friction.mu_c"));
  top_sim_test::note("trajectory fit s_c", r.value("friction.s_c"));
  top_sim_test::note("trajectory fit s_c error", r.error("friction.s_c"));
  top_sim_test::note("trajectory fit chi2/dof", r.chi2 / r.dof);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.value("friction.mu_c"), 0.31, 0.0031);
  EXPECT_NEAR(r.value("friction.s_c"), 0.52, 0.0052);
  EXPECT_EQ(r.dof, 398);
}

TEST(TrajectoryFit, RejectsUnknownParametersAndTooFewSamples) {
  const Scene scene = top_sim_test::scene_from(top_sim_test::standard_scene(0.1, 200.0));
  const std::vector<ContactSample> data = {{0.01, 0.0, 0.0}};
  try {
    fit_trajectory(scene, data, {"friction.mu"});
    FAIL() << "no error";
  } catch (const FitError& e) {
    EXPECT_NE(std::string(e.what()).find("friction.mu_c"), std::string::npos) << e.what();  // lists the choices
  }
  EXPECT_THROW(fit_trajectory(scene, data, {"friction.mu_c", "friction.s_c", "initial.tilt"}), FitError);
}

// ---- data files and the command line ----

std::string error_of(const std::string& csv, bool trajectory = false) {
  std::istringstream in(csv);
  try {
    if (trajectory) read_trajectory_data(in, "data.csv");
    else read_stationary_data(in, "data.csv");
  } catch (const FitError& e) {
    return e.what();
  }
  return "";
}

TEST(FitData, MissingColumnAndNonNumericValueAreNamed) {
  EXPECT_NE(error_of("alpha,sigma\n0.1,0.2\n").find("missing column 'phi'"), std::string::npos);
  const std::string e = error_of("alpha,phi\n0.1,0.2\n0.1,abc\n");
  EXPECT_NE(e.find("row 2, column 'phi': 'abc' is not a number"), std::string::npos) << e;
  EXPECT_NE(error_of("t,contact_x\n0,0\n", true).find("missing column 'contact_y'"), std::string::npos);
  EXPECT_NE(error_of("alpha,phi,sigma_alpha\n0.1,0.2,0.01\n").find("sigma_phi"), std::string::npos);
  // top_sim_run's CSV: text columns (regime) are ignored, rows in any order or subset.
  std::istringstream run("t,alpha,contact_x,contact_y,regime\n0.5,0.1,1e-3,2e-3,nutating\n");
  const auto d = read_trajectory_data(run, "run.csv");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_DOUBLE_EQ(d[0].y, 2e-3);
}

using Cli = top_sim_test::CliResult;

Cli run_fit_cli(const std::string& args) { return top_sim_test::run_binary(TOP_SIM_TEST_FIT_BINARY, args); }

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path =
      std::filesystem::temp_directory_path() / ("top_sim_fit_test_" + std::to_string(getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

TEST(FitCli, BadDataExitsTwoWithAClearMessage) {
  const std::string missing = write_temp("missing.csv", "alpha,phy\n0.1,0.2\n");
  Cli r = run_fit_cli("stationary '" + missing + "' --law paper");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing column 'phi'"), std::string::npos) << r.err;
  const std::string text = write_temp("text.csv", "alpha,phi\n0.1,0.2\n0.12,x\n0.13,0.3\n");
  r = run_fit_cli("stationary '" + text + "' --law paper");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("row 2, column 'phi': 'x' is not a number"), std::string::npos) << r.err;
  const std::string few = write_temp("few.csv", "alpha,phi,sigma_alpha,sigma_phi\n0.1,0.2,0.01,0.01\n");
  r = run_fit_cli("stationary '" + few + "' --law paper");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("1 point is fewer than the 2 parameters"), std::string::npos) << r.err;  // singular for one
  const std::string inf = write_temp("inf.csv", "alpha,phi\n0.1,0.2\n0.1,inf\n0.2,0.3\n");
  r = run_fit_cli("stationary '" + inf + "' --law paper");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("point 2: phi = inf"), std::string::npos) << r.err;
  r = run_fit_cli("trajectory '" + few + "' --scene '" + top_sim_test::scene_path("default") + "' --free friction.mu_c");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing column 't'"), std::string::npos) << r.err;
  for (const auto& p : {missing, text, few, inf}) std::filesystem::remove(p);
}

TEST(FitCli, StationaryFitWritesTheJsonFields) {
  const std::string json = write_temp("fit.json", "");
  const Cli r = run_fit_cli("stationary '" + top_sim_test::config_dir() +
                            "/../docs/data/fit/stationary_measured.csv' --law paper --json '" + json + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  boost::property_tree::ptree j;  // read by another library than the writer's (nlohmann-json)
  ASSERT_NO_THROW(boost::property_tree::read_json(json, j));
  for (const char* key : {"parameters.mu_c", "parameters.s_c", "uncertainties.mu_c", "covariance.mu_c.mu_c",
                          "covariance.s_c.mu_c", "chi2", "cpu_seconds"})
    EXPECT_TRUE(j.get_child_optional(key)) << key;
  EXPECT_EQ(j.get<int>("dof"), 22);  // 24 points, 2 parameters
  // The uncertainty is the square root of the covariance's diagonal: both written at full precision.
  const double sigma = j.get<double>("uncertainties.mu_c"), variance = j.get<double>("covariance.mu_c.mu_c");
  EXPECT_NEAR(variance, sigma * sigma, 1e-12 * variance);
  std::filesystem::remove(json);
}

}  // namespace
