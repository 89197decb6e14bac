// Paper Fig. 4 analogue: tan(phi*/2) against tan(alpha), measured by top_sim_sweep's per-point code
// (src/studies/sweep_point.cpp) and compared with physics.md section 5's analytic branches, computed here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../../src/studies/sweep_point.hpp"
#include "top_sim/friction.hpp"

namespace {

using namespace top_sim;

// physics.md section 5, paper law: mu(s) = tan(alpha) at s = s_c (1 -+ sqrt(1 - tan(alpha)/mu_c)).
double stable_branch(double alpha, double mu_c, double s_c) {
  return s_c * (1.0 - std::sqrt(1.0 - std::tan(alpha) / mu_c));
}
double unstable_branch(double alpha, double mu_c, double s_c) {
  return s_c * (1.0 + std::sqrt(1.0 - std::tan(alpha) / mu_c));
}

SweepSettings settings() {
  SweepSettings s;
  s.config_dir = TOP_SIM_TEST_CONFIG_DIR;
  return s;
}

SweepResult sweep(const std::string& top, const std::string& plane, double alpha,
                  SweepStart start = SweepStart::tilted) {
  SweepSettings s = settings();
  s.start = start;
  SweepPoint p;
  p.top = top;
  p.plane = plane;
  p.alpha = alpha;
  return run_sweep_point(p, s);
}

// Below alpha_c the sleeping top's measured direction matches the stable branch; tolerance 1e-5 in
// tan(phi/2): the sweep stops when phi changes by < 1e-6 rad over three windows in a row.
struct Case {
  const char* top;
  const char* plane;
  double mu_c, s_c;  // the plane file's paper law (config/planes/*.yaml)
  double alpha;
};

class StableBranch : public ::testing::TestWithParam<Case> {};

TEST_P(StableBranch, MeasuredTanHalfPhiIsTheAnalyticStableRoot) {
  const Case c = GetParam();
  const SweepResult r = sweep(c.top, c.plane, c.alpha);
  ASSERT_EQ(r.outcome, "sleeping") << "regime " << to_string(r.regime) << " after " << r.sim_seconds << " s";
  ASSERT_TRUE(r.tan_half.has_value());
  const double s_star = stable_branch(c.alpha, c.mu_c, c.s_c);
  EXPECT_NEAR(*r.tan_half, s_star, 1e-5);
  // The CSV's analytic columns are physics.md's roots as well.
  EXPECT_NEAR(r.s_stable, s_star, 1e-9);
  const double s_u = unstable_branch(c.alpha, c.mu_c, c.s_c);
  if (s_u <= 1.0) EXPECT_NEAR(r.s_unstable, s_u, 1e-9);
  else EXPECT_LT(r.s_unstable, 0.0);
}

INSTANTIATE_TEST_SUITE_P(PaperFig4, StableBranch,
                         ::testing::Values(Case{"aluminium", "pmma", 0.25, 0.6, 0.05},
                                           Case{"aluminium", "pmma", 0.25, 0.6, 0.15},
                                           Case{"aluminium", "pmma", 0.25, 0.6, 0.24},
                                           Case{"steel", "pmma", 0.25, 0.6, 0.15},   // other top, same curve
                                           Case{"steel", "steel", 0.20, 0.7, 0.08},
                                           Case{"steel", "steel", 0.20, 0.7, 0.15}));

TEST(PaperFig4, AboveTheCriticalInclinationTheTopSlidesAndTanHalfPhiApproachesOne) {
  // alpha_c = atan(mu_c) = 0.2450 on PMMA; above it no stationary state exists (section 5).
  double previous = 0.0;
  for (double alpha : {0.26, 0.30}) {
    const SweepResult r = sweep("aluminium", "pmma", alpha);
    EXPECT_EQ(r.outcome, "sliding") << "alpha " << alpha;
    EXPECT_FALSE(r.phi_star.has_value());
    EXPECT_LT(r.s_stable, 0.0);
    ASSERT_TRUE(r.tan_half.has_value());
    // After the 30 s run the path is within 2e-3 rad of straight downhill (phi -> pi/2): tan(phi/2) -> 1.
    EXPECT_GT(*r.tan_half, 0.998) << "alpha " << alpha;
    EXPECT_LT(*r.tan_half, 1.0 + 1e-3) << "alpha " << alpha;
    EXPECT_GT(*r.tan_half, previous - 1e-3);
    previous = *r.tan_half;
  }
}

TEST(PaperFig4, JustBelowCriticalATopStartedAtRestRunsAwayButALaunchedOneSleeps) {
  // physics.md section 5: started at rest (s = 1) on PMMA it runs away for alpha in (0.2423, 0.2450);
  // started near the sleeping slip it finds the stable branch, which exists up to alpha_c.
  const double alpha = 0.244;
  const SweepResult from_rest = sweep("aluminium", "pmma", alpha);
  EXPECT_EQ(from_rest.outcome, "sliding");
  const SweepResult launched = sweep("aluminium", "pmma", alpha, SweepStart::launched);
  ASSERT_EQ(launched.outcome, "sleeping");
  EXPECT_NEAR(*launched.tan_half, stable_branch(alpha, 0.25, 0.6), 1e-5);
  // Just below that window the top started at rest still finds the stable branch.
  const SweepResult below = sweep("aluminium", "pmma", 0.24);
  EXPECT_EQ(below.outcome, "sleeping");
}

TEST(PaperFig4, NegativeSpinMirrorsThePath) {
  // Reversing the spin maps phi* -> pi - phi*; the reported tan(phi/2) is mirrored back to s*.
  SweepPoint p;
  p.alpha = 0.15;
  p.spin = -200.0;
  const SweepResult r = run_sweep_point(p, settings());
  ASSERT_EQ(r.outcome, "sleeping");
  const double s_star = stable_branch(0.15, 0.25, 0.6);
  EXPECT_NEAR(*r.phi, M_PI - 2.0 * std::atan(s_star), 2e-5);
  EXPECT_NEAR(*r.tan_half, s_star, 1e-5);
}

TEST(PaperFig4, BadGridPointsNameTheKey) {
  SweepPoint p;
  p.top = "no_such_top";
  EXPECT_THROW(make_sweep_scene(p, settings()), SceneError);
  p = SweepPoint{};
  p.plane = "pmma";
  p.s_c = 1.5;  // outside (0, 1]
  try {
    make_sweep_scene(p, settings());
    FAIL() << "s_c = 1.5 accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("s_c"), std::string::npos) << e.what();
  }
}

// The command-line tool: bad arguments exit 2 naming the flag; a small grid writes a CSV row per point.
std::string sweep_binary() {
  const std::string run = TOP_SIM_TEST_RUN_BINARY;  // top_sim_sweep is built next to top_sim_run
  return run.substr(0, run.rfind('/') + 1) + "top_sim_sweep";
}

TEST(PaperFig4, SweepRefusesAnAlphaOutOfRangeAndWritesOneRowPerAlpha) {
  const std::string bin = sweep_binary();
  if (std::FILE* f = std::fopen(bin.c_str(), "r")) std::fclose(f);
  else GTEST_SKIP() << bin << " not built";
  const std::string err = ::testing::TempDir() + "sweep_err.txt";
  const int bad = std::system((bin + " --alpha 2 2> " + err).c_str());
  EXPECT_EQ(WEXITSTATUS(bad), 2);
  std::FILE* f = std::fopen(err.c_str(), "r");
  ASSERT_NE(f, nullptr);
  char buf[512] = {};
  const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
  std::fclose(f);
  EXPECT_NE(std::string(buf, n).find("--alpha = '2': must be in (0, pi/2)"), std::string::npos) << buf;

  const std::string csv = ::testing::TempDir() + "sweep.csv";
  const int ok = std::system((bin + " --alpha 0.26,0.3 --threads 2 --config " TOP_SIM_TEST_CONFIG_DIR " --out " + csv +
                              " 2>/dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(ok), 0);
  f = std::fopen(csv.c_str(), "r");
  ASSERT_NE(f, nullptr);
  int lines = 0;
  for (int c; (c = std::fgetc(f)) != EOF;) lines += c == '\n';
  std::fclose(f);
  EXPECT_EQ(lines, 3);  // header + two points
}

}  // namespace
