// The command line top_sim_run (docs/interfaces.md): exit codes, messages on stderr, JSON summary, CSV columns.
// Boost 1.74's property_tree pulls in boost/bind.hpp, which otherwise warns about its global placeholders.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#include <gtest/gtest.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_util.hpp"
#include "test_util.hpp"

namespace {

namespace pt = boost::property_tree;

using top_sim_test::CliResult;
using top_sim_test::contains;
using top_sim_test::in_scratch;
using top_sim_test::slurp;

CliResult run_cli(const std::string& args) { return top_sim_test::run_binary(TOP_SIM_TEST_RUN_BINARY, args); }

TEST(Cli, BadSceneExitsTwoAndNamesFileKeyValueRange) {
  const std::string path = top_sim_test::fixture_path("bad_inclination");
  const CliResult r = run_cli("'" + path + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  EXPECT_TRUE(contains(r.err, "plane.inclination: 2 is out of range")) << r.err;
  EXPECT_TRUE(contains(r.err, "(-pi/2, pi/2)")) << r.err;
}

TEST(Cli, BadArgumentsExitTwoAndNameTheArgument) {
  const std::string scene = "'" + top_sim_test::scene_path("default") + "'";
  CliResult r = run_cli(scene + " --duration -1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--duration = '-1'")) << r.err;
  EXPECT_TRUE(contains(r.err, "> 0")) << r.err;  // the allowed range
  r = run_cli(scene + " --rate fast");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--rate = 'fast'")) << r.err;
  r = run_cli(scene + " --frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--frobnicate")) << r.err;
  r = run_cli(scene + " --summary");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--summary")) << r.err;
  r = run_cli("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "no scene file")) << r.err;
  r = run_cli("'" + in_scratch("missing.yaml") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "missing.yaml: cannot open")) << r.err;
}

// top_sim_run on a test fixture with its summary read back: the exit status and the summary's JSON.
struct FixtureRun {
  CliResult result;
  pt::ptree summary;
};
FixtureRun run_fixture(const std::string& fixture) {
  FixtureRun f;
  const std::string summary = in_scratch(fixture + ".json");
  f.result = run_cli("'" + top_sim_test::fixture_path(fixture) + "' --summary '" + summary + "'");
  EXPECT_NO_THROW(pt::read_json(summary, f.summary)) << slurp(summary);
  return f;
}

// A top that falls with no shape to catch it has reached an end of its story (physics.md section 8): exit 0, the end
// state named, no contact fault.
TEST(Cli, AFallIsAnEndAndExitsZero) {
  const FixtureRun f = run_fixture("falls_over");
  EXPECT_EQ(f.result.exit_code, 0) << f.result.err;
  EXPECT_FALSE(contains(f.result.err, "contact fault")) << f.result.err;
  EXPECT_EQ(f.summary.get<std::string>("regime"), "fallen");
  EXPECT_EQ(f.summary.get<std::string>("contact_fault"), "null");
  EXPECT_EQ(f.summary.get<std::string>("end_state"), "fallen");
  EXPECT_TRUE(contains(f.summary.get<std::string>("end_state_message"), "max_tilt"));
}

// A fault stays a fault: Painleve's paradox (the fixture's large friction on a steep top) exits 3.
TEST(Cli, ContactFaultExitsThree) {
  const FixtureRun f = run_fixture("painleve");
  EXPECT_EQ(f.result.exit_code, 3) << f.result.err;
  EXPECT_TRUE(contains(f.result.err, "contact fault")) << f.result.err;
  EXPECT_EQ(f.summary.get<std::string>("regime"), "contact_fault");
  EXPECT_TRUE(contains(f.summary.get<std::string>("contact_fault"), "Painleve"));
}

TEST(Cli, DefaultSceneSummaryHasTheDocumentedKeysAndSleepsAtPhiStar) {
  const std::string summary = in_scratch("default.json");
  const CliResult r = run_cli("'" + top_sim_test::scene_path("default") + "' --summary '" + summary + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  pt::ptree j;
  ASSERT_NO_THROW(pt::read_json(summary, j)) << slurp(summary);
  for (const char* key : {"sim_seconds", "cpu_seconds", "steps", "rhs_evaluations", "regime", "phi_measured", "phi_star",
                          "final", "final.position", "final.velocity", "final.f_hat", "final.omega", "final.rotor_spin",
                          "final.drilling_torque", "final.patch_radius", "final.touching", "energy_balance_residual",
                          "contact_fault"})
    EXPECT_TRUE(j.get_child_optional(key)) << "missing key " << key;
  EXPECT_EQ(j.get<double>("final.drilling_torque"), 0.0);  // the default scene's point contact
  EXPECT_EQ(j.get<double>("final.patch_radius"), 0.0);
  EXPECT_EQ(j.get<int>("final.touching"), 1);  // a body without shapes touches with its tip sphere, bit 0
  // Boost's JSON reader keeps null as the text "null".
  EXPECT_EQ(j.get<std::string>("contact_fault"), "null");
  EXPECT_EQ(j.get<std::string>("final.rotor_spin"), "null");  // no rotor on this top
  EXPECT_EQ(j.get<std::string>("regime"), "sleeping");
  EXPECT_NEAR(j.get<double>("sim_seconds"), 300.0, 1e-9);  // the scene's duration
  EXPECT_GT(j.get<long>("steps"), 0);
  EXPECT_GE(j.get<long>("rhs_evaluations"), j.get<long>("steps"));
  const double phi_measured = j.get<double>("phi_measured"), phi_star = j.get<double>("phi_star");
  // The acceptance criterion: within 1e-3 rad; phi_star is physics.md's formula (printed to 17 digits).
  EXPECT_NEAR(phi_measured, phi_star, 1e-3);
  EXPECT_NEAR(phi_star, top_sim_test::paper_phi_star(0.1, 0.25, 0.6), 1e-15);
  EXPECT_LT(j.get<double>("energy_balance_residual"), 1e-6);
  EXPECT_EQ(j.get_child("final.position").size(), 2u);
  EXPECT_EQ(j.get_child("final.velocity").size(), 2u);
  EXPECT_EQ(j.get_child("final.f_hat").size(), 3u);
  EXPECT_EQ(j.get_child("final.omega").size(), 3u);
  // The final velocity points along phi (angle from h towards downhill, -e_y).
  std::vector<double> v;
  for (const auto& kv : j.get_child("final.velocity")) v.push_back(kv.second.get_value<double>());
  EXPECT_NEAR(std::atan2(-v[1], v[0]), phi_star, 1e-3);
  top_sim_test::note("CLI default scene: |phi_measured - phi_star|", std::abs(phi_measured - phi_star));
  top_sim_test::note("CLI default scene: cpu_seconds", j.get<double>("cpu_seconds"));
}

TEST(Cli, SummaryToStandardOutput) {
  const CliResult r = run_cli("'" + top_sim_test::scene_path("upright") + "' --duration 0.5 --summary -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  pt::ptree j;
  std::istringstream in(r.out);
  ASSERT_NO_THROW(pt::read_json(in, j)) << r.out;
  EXPECT_NEAR(j.get<double>("sim_seconds"), 0.5, 1e-12);
  EXPECT_EQ(j.get<std::string>("phi_star"), "null");  // an upright top at alpha 0 has no direction of travel
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  return out;
}

TEST(Cli, CsvHasTheDocumentedColumnsAtTheRequestedRate) {
  const std::string csv = in_scratch("default.csv");
  const CliResult r =
      run_cli("'" + top_sim_test::scene_path("default") + "' --duration 1 --rate 10 --csv '" + csv + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(csv);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const std::vector<std::string> header = split(line);
  // docs/interfaces.md: t, position and velocity of the centre of mass, contact point, f_hat, omega, s, mu, N, phi,
  // regime, energy, energy-balance residual.
  for (const char* col : {"t", "com_x", "com_y", "com_z", "vcm_x", "vcm_y", "vcm_z", "contact_x", "contact_y", "f_x",
                          "f_y", "f_z", "omega_x", "omega_y", "omega_z", "s", "mu", "N", "phi", "regime", "energy",
                          "energy_residual"})
    EXPECT_NE(std::find(header.begin(), header.end(), col), header.end()) << "missing column " << col << ": " << line;
  // Columns added later come last, in the order they were added: the columns before keep their positions.
  ASSERT_GE(header.size(), 3u);
  EXPECT_EQ(header[header.size() - 3], "drilling_torque") << line;
  EXPECT_EQ(header[header.size() - 2], "patch_radius") << line;
  EXPECT_EQ(header.back(), "touching") << line;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(split(line));
  // 1 s at 10 Hz: t = 0, 0.1, ..., 1.0.
  ASSERT_EQ(rows.size(), 11u);
  const auto t_col = std::find(header.begin(), header.end(), "t") - header.begin();
  const auto regime_col = std::find(header.begin(), header.end(), "regime") - header.begin();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size()) << "row " << k;
    EXPECT_NEAR(std::stod(rows[k][t_col]), 0.1 * k, 1e-9);
    const std::string& regime = rows[k][regime_col];
    EXPECT_TRUE(regime == "nutating" || regime == "precessing" || regime == "sleeping" || regime == "sliding" ||
                regime == "contact_fault")
        << regime;
  }
}

// physics.md section 12: an upright top pivoting on a patch of radius a with Coulomb mu on a level plane has
// n . M_n = -mu m g (3 pi a / 16) (Hertzian pressure); the CSV and the summary's final block carry it and a.
TEST(Cli, FiniteContactColumnsCarryTheDrillingTorqueAndPatch) {
  const double mass = 0.025, g = 9.81, mu = 0.3, a = 2.0e-4;
  const std::string scene = in_scratch("pivoting.yaml"), csv = in_scratch("pivoting.csv"),
                    summary = in_scratch("pivoting.json");
  std::ofstream(scene) << "top: {mass: " << top_sim_test::num(mass)
                       << ", tip_radius: 1.5e-3, com_offset: 0.01, inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6}\n"
                       << "plane: {inclination: 0.0, gravity: " << top_sim_test::num(g) << "}\n"
                       << "friction: {law: coulomb, mu: " << top_sim_test::num(mu) << "}\n"
                       << "contact: {patch_radius: " << top_sim_test::num(a) << "}\n"
                       << "initial: {start: tilted, tilt: 0.0, spin: 100.0}\n";
  const CliResult r =
      run_cli("'" + scene + "' --duration 0.2 --rate 10 --csv '" + csv + "' --summary '" + summary + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double expected = -mu * mass * g * 3.0 * M_PI * a / 16.0;
  std::ifstream in(csv);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const std::vector<std::string> header = split(line);
  const auto torque_col = std::find(header.begin(), header.end(), "drilling_torque") - header.begin();
  const auto patch_col = std::find(header.begin(), header.end(), "patch_radius") - header.begin();
  ASSERT_LT(patch_col, static_cast<long>(header.size())) << line;
  int rows = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> row = split(line);
    ASSERT_EQ(row.size(), header.size());
    EXPECT_NEAR(std::stod(row[torque_col]), expected, 1e-6 * std::abs(expected)) << "row " << rows;
    EXPECT_EQ(std::stod(row[patch_col]), a) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 3);
  pt::ptree j;
  ASSERT_NO_THROW(pt::read_json(summary, j)) << slurp(summary);
  EXPECT_NEAR(j.get<double>("final.drilling_torque"), expected, 1e-6 * std::abs(expected));
  EXPECT_EQ(j.get<double>("final.patch_radius"), a);
}

// A thin disc (physics.md section 13) dropped 10 mm with no spin: in free fall until t = sqrt(2 h / g), touching 0;
// on its rim from then on, touching 1 (bit 0, its one shape); it tips over and ends lying flat, exit 0, the
// summary's end_state lying_flat and final.touching 1.
TEST(Cli, DroppedDiscTouchesAfterFreeFallAndEndsLyingFlat) {
  const double h = 0.01, g = 9.81, rate = 1000.0, duration = 5.0;
  const std::string scene = in_scratch("dropped_disc.yaml"), csv = in_scratch("dropped_disc.csv"),
                    summary = in_scratch("dropped_disc.json");
  std::ofstream(scene) << "top: {mass: 0.4, inertia_axial: 3.2e-4, inertia_transverse: 1.6e-4, "
                          "shapes: [{rim: {offset: 0, radius: 0.04}}]}\n"
                       << "plane: {inclination: 0, gravity: " << top_sim_test::num(g) << "}\n"
                       << "friction: {law: coulomb, mu: 0.3, static: 0.3}\n"
                       << "initial: {tilt: 0.5, spin: 0, angular_velocity_transverse: [0, 0], gap: "
                       << top_sim_test::num(h) << "}\n";
  const CliResult r = run_cli("'" + scene + "' --duration " + top_sim_test::num(duration) + " --rate " +
                              top_sim_test::num(rate) + " --csv '" + csv + "' --summary '" + summary + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double t_touch = std::sqrt(2.0 * h / g);
  std::ifstream in(csv);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const std::vector<std::string> header = split(line);
  auto column = [&header](const char* name) { return std::find(header.begin(), header.end(), name) - header.begin(); };
  const auto t_col = column("t"), touching_col = column("touching"), mode_col = column("contact_mode");
  ASSERT_LT(touching_col, static_cast<long>(header.size())) << line;
  int before = 0, after = 0;
  double first_touch = -1.0;
  std::string last_touching;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> row = split(line);
    ASSERT_EQ(row.size(), header.size());
    const double t = std::stod(row[t_col]);
    EXPECT_EQ(row[touching_col], row[mode_col] == "flight" ? "0" : "1") << "t = " << t << " " << row[mode_col];
    if (t < t_touch) {
      EXPECT_EQ(row[touching_col], "0") << "t = " << t << ": in free fall";
      ++before;
    } else {
      ++after;
    }
    if (row[touching_col] == "1" && first_touch < 0.0) first_touch = t;
    last_touching = row[touching_col];
  }
  EXPECT_EQ(before, static_cast<int>(std::floor(t_touch * rate)) + 1);  // t = 0, 1 ms, ..., 45 ms
  EXPECT_GT(after, 0);
  // The first sample on the rim is the first one at or after the touchdown.
  EXPECT_GE(first_touch, t_touch);
  EXPECT_LE(first_touch, t_touch + 1.0 / rate);
  EXPECT_EQ(last_touching, "1");  // lying flat on its rim
  pt::ptree j;
  ASSERT_NO_THROW(pt::read_json(summary, j)) << slurp(summary);
  EXPECT_EQ(j.get<int>("final.touching"), 1);
  EXPECT_EQ(j.get<std::string>("end_state"), "lying_flat");
  EXPECT_TRUE(contains(j.get<std::string>("end_state_message"), "lying_flat")) << j.get<std::string>("end_state_message");
  EXPECT_EQ(j.get<std::string>("contact_fault"), "null");
  EXPECT_LT(j.get<double>("sim_seconds"), duration);  // the run stopped at the end state
}

}  // namespace

namespace {

// A shipped scene by name runs the scene file of that name (found next to the core library, as installed); an
// unknown name is exit 2 with the shipped names listed.
TEST(Cli, ShippedSceneByNameIsItsFile) {
  const std::string args = " --duration 0.2 --summary -";
  const CliResult by_name = run_cli("tippe_top" + args);
  ASSERT_EQ(by_name.exit_code, 0) << by_name.err;
  const CliResult by_path = run_cli("'" + top_sim_test::scene_path("tippe_top") + "'" + args);
  ASSERT_EQ(by_path.exit_code, 0) << by_path.err;
  pt::ptree a, b;
  std::istringstream ia(by_name.out), ib(by_path.out);
  pt::read_json(ia, a);
  pt::read_json(ib, b);
  std::ostringstream fa, fb;
  pt::write_json(fa, a.get_child("final"));
  pt::write_json(fb, b.get_child("final"));
  EXPECT_EQ(fa.str(), fb.str());
  const CliResult unknown = run_cli("no_such_scene --duration 0.2");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.err;
  EXPECT_TRUE(contains(unknown.err, "no_such_scene: no shipped scene has this name")) << unknown.err;
  for (const auto& entry : std::filesystem::directory_iterator(top_sim_test::config_dir() + "/scenes"))
    EXPECT_TRUE(contains(unknown.err, entry.path().stem().string())) << unknown.err;
}

// Issue 11: a directory as the scene is exit 2 (it aborted); output that cannot be written is exit 1 (it was 0).
TEST(Cli, DirectoryAsSceneExitsTwo) {
  const CliResult r = run_cli("'" + top_sim_test::config_dir() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "is a directory")) << r.err;
}

TEST(Cli, OutputThatCannotBeWrittenExitsOne) {
  const std::string scene = "'" + top_sim_test::scene_path("default") + "' --duration 0.5";
  CliResult r = run_cli(scene + " --csv /dev/full");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "--csv = '/dev/full': writing failed")) << r.err;
  r = run_cli(scene + " --summary /dev/full");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "--summary = '/dev/full': writing failed")) << r.err;
}

}  // namespace

namespace {

TEST(Cli, CsvLargerThanTheLimitIsRefusedBeforeRunning) {
  const CliResult r = run_cli("'" + top_sim_test::scene_path("default") + "' --duration 10 --rate 1e9 --csv '" +
                              in_scratch("huge.csv") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "must be <= 1e8 rows")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(in_scratch("huge.csv")));
}

TEST(Cli, QuietAndProgressAreAccepted) {
  const CliResult r = run_cli("'" + top_sim_test::scene_path("default") + "' --duration 1 --quiet --progress");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
