// The command line top_sim_stability (docs/interfaces.md): exit codes, messages naming argument, value and range,
// the JSON fields, the sweeps' alpha_c and spin windows, the plot.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#include <gtest/gtest.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "cli_util.hpp"
#include "test_util.hpp"

namespace {

namespace pt = boost::property_tree;

using top_sim_test::CliResult;
using top_sim_test::contains;
using top_sim_test::scratch;
using top_sim_test::slurp;

CliResult run(const std::string& args) { return top_sim_test::run_binary(TOP_SIM_TEST_STABILITY_BINARY, args); }

std::string scene(const std::string& name) { return "'" + top_sim_test::scene_path(name) + "'"; }

TEST(StabilityCli, BadArgumentsExitTwoNamingArgumentValueAndRange) {
  struct Case {
    std::string args, says, range;
  };
  const Case cases[] = {
      {" --spin 0", "--spin = '0'", "nonzero and in [-1e6, 1e6]"},
      {" --spin 2e6", "--spin = '2e6'", "in [-1e6, 1e6]"},
      {" --spin fast", "--spin = 'fast'", "not a finite number"},
      {" --sweep-alpha 0:0.2:10", "--sweep-alpha = '0:0.2:10'", "in (0, pi/2)"},
      {" --sweep-alpha 0.1:0.2:0", "--sweep-alpha = '0.1:0.2:0'", "an integer in [1, 10000]"},
      {" --sweep-alpha 0.2:0.1:5", "--sweep-alpha = '0.2:0.1:5'", "FROM <= TO"},
      {" --sweep-spin -1:1", "--sweep-spin = '-1:1'", "FROM:TO:N"},
      {" --sweep-spin -2e6:1:3", "--sweep-spin = '-2e6:1:3'", "in [-1e6, 1e6]"},
      {" --plot x.png", "--plot = 'x.png'", "needs --sweep-alpha or --sweep-spin"},
      {" --json", "--json", "needs a value"},
      {" --frobnicate", "'--frobnicate'", "unknown option"},
  };
  for (const Case& c : cases) {
    const CliResult r = run(scene("default") + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.says)) << c.args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.range)) << c.args << "\n" << r.err;
  }
  CliResult r = run("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "no scene file")) << r.err;
  r = run("'" + top_sim_test::fixture_path("bad_inclination") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "plane.inclination")) << r.err;
}

TEST(StabilityCli, NoSleepingStateExitsThreeWithTheReason) {
  const CliResult r = run(scene("supercritical"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "no sleeping state to analyse")) << r.err;
  EXPECT_TRUE(contains(r.err, "slides downhill")) << r.err;
}

// A body with a rim (Euler's disk) is refused naming top.shapes and why, exit 2, not analysed as if a tip sphere.
TEST(StabilityCli, BodyWithARimIsRefusedNamingTopShapes) {
  for (const char* name : {"euler_disk", "tippe_top_stem"}) {  // a rim; two spheres
    const CliResult r = run(scene(name));
    EXPECT_EQ(r.exit_code, 2) << name << r.err;
    EXPECT_TRUE(contains(r.err, "top.shapes")) << r.err;
    EXPECT_TRUE(contains(r.err, "tip sphere only")) << r.err;
  }
}

TEST(StabilityCli, JsonHasExactlyTheDocumentedFields) {
  const std::string path = scratch() + "/default.json";
  const CliResult r = run(scene("default") + " --json '" + path + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  pt::ptree j;
  ASSERT_NO_THROW(pt::read_json(path, j)) << slurp(path);
  std::set<std::string> keys;
  for (const auto& kv : j) keys.insert(kv.first);
  EXPECT_EQ(keys, (std::set<std::string>{"eigenvalues", "modes", "stable", "relaxation_time", "spin", "alpha"}));
  std::set<std::string> modes;
  for (const auto& kv : j.get_child("modes")) modes.insert(kv.first);
  EXPECT_EQ(modes, (std::set<std::string>{"precession", "nutation", "friction"}));
  EXPECT_EQ(j.get_child("eigenvalues").size(), 7u);
  for (const auto& e : j.get_child("eigenvalues")) EXPECT_EQ(e.second.size(), 2u);  // [re, im]
  EXPECT_EQ(j.get_child("modes.friction").size(), 2u);
  const auto& prec = j.get_child("modes.precession");
  EXPECT_NEAR(prec.front().second.get_value<double>(), -0.029, 0.0005);
  EXPECT_EQ(j.get<std::string>("stable"), "true");
  EXPECT_NEAR(j.get<double>("relaxation_time"), 34.03, 0.01);
  EXPECT_EQ(j.get<double>("spin"), 200.0);
  EXPECT_EQ(j.get<double>("alpha"), 0.1);
  // --json - puts the JSON alone on standard output (the report goes to standard error).
  const CliResult s = run(scene("default") + " --spin -400 --json -");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  std::istringstream in(s.out);
  ASSERT_NO_THROW(pt::read_json(in, j)) << s.out;
  EXPECT_EQ(j.get<double>("spin"), -400.0);
  EXPECT_TRUE(contains(s.err, "relaxation time")) << s.err;
}

TEST(StabilityCli, SweepsReportAlphaCAndTheGyrostatWindow) {
  CliResult r = run(scene("default") + " --sweep-alpha 0.05:0.25:5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "alpha_c located")) << r.out;
  EXPECT_TRUE(contains(r.out, "alpha = 0.2449786631 rad")) << r.out;
  EXPECT_TRUE(contains(r.out, "atan(mu_c) = 0.2449786631")) << r.out;
  EXPECT_TRUE(contains(r.out, "no sleeping state")) << r.out;  // alpha 0.25 > alpha_c
  r = run(scene("gyro_reversal") + " --sweep-spin -1:1:21");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "spin windows where Re nutation > 0 (edges bisected): [-0.55189")) << r.out;
}

// An ordinary top's upright state (docs/analysis.md "The wake-up"): the critical spin next to Maxwell-Klein.
TEST(StabilityCli, OrdinaryTopUprightReportsTheCriticalSpin) {
  const CliResult r = run(scene("spin_down") + " --state upright --sweep-spin 0:100:51");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "Maxwell-Klein critical spin (frictionless plane, I_f^2 w^2 = 4 I_d m g f): 34.31")) << r.out;
  EXPECT_TRUE(contains(r.out, "critical spin (largest Re but the zero one crosses 1e-7 1/s, bisected): ")) << r.out;
  EXPECT_TRUE(contains(r.out, "rad/s (stable above; precession")) << r.out;
  EXPECT_TRUE(contains(r.out, "unstable below, stable above")) << r.out;
}

// A tippe top (docs/interfaces.md): --state's errors exit 2 naming option and value, an inclined plane exits 3.
TEST(StabilityCli, StateErrorsNameTheOptionAndValue) {
  struct Case {
    std::string scene, args, says, allowed;
    int exit_code;
  };
  const Case cases[] = {
      {"tippe_top", " --state sideways", "--state = 'sideways'", "upright or inverted", 2},
      {"default", " --state upright", "plane.inclination = 0.1", "level plane only", 3},  // an ordinary top
      {"tippe_top", "", "top.com_offset = -0.005", "give --state upright|inverted", 2},
      {"tippe_top", " --sweep-alpha 0.1:0.2:3", "--sweep-alpha", "level plane only", 2},
  };
  for (const Case& c : cases) {
    const CliResult r = run(scene(c.scene) + c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.says)) << c.args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.allowed)) << c.args << "\n" << r.err;
  }
  const std::string tilted = scratch() + "/tilted_tippe.yaml";
  std::ofstream(tilted) << "top: {mass: 0.015, tip_radius: 0.025, com_offset: -0.005, "
                                            "inertia_axial: 3.75e-6, inertia_transverse: 3.75e-6, max_tilt: 3.14159}\n"
                                            "plane: {inclination: 0.1}\nfriction: {law: coulomb, mu: 0.3, "
                                            "regularization_speed: 1.0e-2}\ninitial: {spin: 100.0}\n";
  const CliResult r = run("'" + tilted + "' --state upright");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "plane.inclination = 0.1 rad")) << r.err;
  EXPECT_TRUE(contains(r.err, "(plane.inclination 0)")) << r.err;
}

// The JSON of a spinning state: the documented fields plus "state"; the verdicts on both sides of Magnus' critical
// spins (tippe_top.yaml: omega_k^2 = m g a / c = 627.84 upright, 1412.64 inverted, docs/analysis.md).
TEST(StabilityCli, SpinningStateJsonAndVerdicts) {
  struct Case {
    std::string state;
    double spin;
    bool stable;
  };
  const Case cases[] = {{"upright", 20.0, true}, {"upright", 30.0, false}, {"inverted", 30.0, false},
                        {"inverted", 45.0, true}};
  for (const Case& c : cases) {
    const CliResult r = run(scene("tippe_top") + " --state " + c.state + " --spin " + std::to_string(c.spin) + " --json -");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    pt::ptree j;
    std::istringstream in(r.out);
    ASSERT_NO_THROW(pt::read_json(in, j)) << r.out;
    std::set<std::string> keys;
    for (const auto& kv : j) keys.insert(kv.first);
    EXPECT_EQ(keys, (std::set<std::string>{"state", "eigenvalues", "modes", "stable", "relaxation_time", "spin", "alpha"}));
    EXPECT_EQ(j.get<std::string>("state"), c.state);
    EXPECT_EQ(j.get<std::string>("stable"), c.stable ? "true" : "false") << c.state << " " << c.spin;
    EXPECT_EQ(j.get_child("eigenvalues").size(), 7u);
    EXPECT_TRUE(contains(r.err, "Magnus' critical spin")) << r.err;
  }
}

// --sweep-spin without --state sweeps both states; each crossing within 1e-6 of Magnus' omega_k.
TEST(StabilityCli, SweepSpinOfATippeTopLocatesBothCrossings) {
  const CliResult r = run(scene("tippe_top") + " --sweep-spin 0:100:21");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto edge = [&r](const std::string& prefix) {
    const std::size_t at = r.out.find(prefix);
    return at == std::string::npos ? NAN : std::stod(r.out.substr(at + prefix.size()));
  };
  const std::string windows = ": spin windows where the largest Re but the zero one > 0 (edges bisected): [";
  EXPECT_NEAR(edge("upright" + windows) / std::sqrt(627.84), 1.0, 1e-6) << r.out;
  EXPECT_NEAR(edge("inverted" + windows + "0, ") / std::sqrt(1412.64), 1.0, 1e-6) << r.out;
}

TEST(StabilityCli, PlotWritesAPng) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") != 0) GTEST_SKIP() << "no python3-matplotlib";
  const std::string png = scratch() + "/sweep.png";
  const CliResult r = run(scene("default") + " --sweep-alpha 0.05:0.24:4 --plot '" + png + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
}

TEST(StabilityCli, PlotThatFailsExitsOne) {
  // The plot script failing (here: an interpreter that always fails) is exit 1, after the sweep's report.
  const std::string cmd = "TOP_SIM_PYTHON=/bin/false ";
  const std::string out = scratch() + "/o.txt", err = scratch() + "/e.txt";
  const int status = std::system((cmd + "'" + TOP_SIM_TEST_STABILITY_BINARY + "' " + scene("default") +
                                  " --sweep-alpha 0.05:0.24:4 --plot '" + scratch() + "/y.png' >'" + out + "' 2>'" + err + "'")
                                     .c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_TRUE(contains(slurp(err), "--plot = '")) << slurp(err);
  EXPECT_TRUE(contains(slurp(out), "alpha_c located")) << slurp(out);
}

}  // namespace
