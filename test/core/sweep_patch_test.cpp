// top_sim_sweep's --patch-radius (issue 32 part 7): the parser's items and errors, the grid's order, the scene
// each point gets, and the CSV's last column.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../src/studies/sweep_options.hpp"
#include "../../src/studies/sweep_point.hpp"
#include "../../src/output/arguments.hpp"
#include "top_sim/model.hpp"

namespace {

using namespace top_sim;

SweepOptions parsed(const std::vector<std::string>& args) {
  SweepOptions o;
  EXPECT_TRUE(parse_sweep_options(args, o));
  return o;
}

// The BadArgument message of `args`, "" when they were accepted.
std::string refusal(const std::vector<std::string>& args) {
  SweepOptions o;
  try {
    parse_sweep_options(args, o);
  } catch (const top_sim_cli::BadArgument& e) {
    return e.message;
  }
  return "";
}

SweepSettings settings() {
  SweepSettings s;
  s.config_dir = TOP_SIM_TEST_CONFIG_DIR;
  return s;
}

TEST(SweepPatchRadius, DefaultIsThePointContact) {
  const SweepOptions o = parsed({"--alpha", "0.1"});
  ASSERT_EQ(o.patches.size(), 1u);
  EXPECT_FALSE(o.patches[0].hertz);
  EXPECT_EQ(o.patches[0].metres, 0.0);
  EXPECT_TRUE(point_contact(make_sweep_scene(make_sweep_grid(o)[0], settings()).model));
}

TEST(SweepPatchRadius, ItemsAreNumbersOrHertz) {
  const SweepOptions o = parsed({"--alpha", "0.1,0.2", "--patch-radius", "0,2e-5,hertz"});
  ASSERT_EQ(o.patches.size(), 3u);
  EXPECT_EQ(o.patches[1].metres, 2e-5);
  EXPECT_TRUE(o.patches[2].hertz);
  // The patch radius sits outside spin and alpha: each patch's rows are a block of the alphas.
  const std::vector<SweepPoint> grid = make_sweep_grid(o);
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid[0].alpha, 0.1);
  EXPECT_EQ(grid[1].alpha, 0.2);
  EXPECT_EQ(grid[2].patch.metres, 2e-5);
  EXPECT_TRUE(grid[5].patch.hertz);
  EXPECT_EQ(parsed({"--patch-radius", "0:1e-4:3"}).patches[2].metres, 1e-4);
}

TEST(SweepPatchRadius, BadValuesNameTheFlagValueAndRange) {
  for (const char* bad : {"-1e-3", "nan", "inf", "hertzz", "0,hertzz", "hertz,-1", "hertz,", ""}) {
    const std::string m = refusal({"--patch-radius", bad});
    EXPECT_NE(m.find(std::string("--patch-radius = '") + bad + "'"), std::string::npos) << bad << ": " << m;
  }
  EXPECT_NE(refusal({"--patch-radius", "-1"}).find(">= 0 [m], or hertz"), std::string::npos);
  for (const char* bad : {"hertzz", "nan", "0,nan", "0:nan:3", "-1:0:3"})
    EXPECT_NE(refusal({"--patch-radius", bad}).find(">= 0 [m], or hertz"), std::string::npos) << bad;
  EXPECT_NE(refusal({"--patch-radius"}).find("needs a value"), std::string::npos);
}

TEST(SweepPatchRadius, ThePointsSceneGetsThePatch) {
  SweepPoint p;
  p.patch = PatchRadius{3e-5, false};
  const Scene fixed = make_sweep_scene(p, settings());
  EXPECT_EQ(fixed.model.finite_contact.patch_radius, 3e-5);
  EXPECT_FALSE(fixed.model.finite_contact.hertz);
  p.patch = PatchRadius{0.0, true};
  const Scene hertz = make_sweep_scene(p, settings());
  EXPECT_TRUE(hertz.model.finite_contact.hertz);
  EXPECT_GT(hertz.model.finite_contact.effective_modulus, 0.0);
}

TEST(SweepPatchRadius, HertzWithoutMaterialsNamesTheFlag) {
  const std::string top = ::testing::TempDir() + "sweep_patch_bare_top.yaml";
  {
    std::ofstream f(top);  // a top without young_modulus and poisson_ratio
    f << "mass: 0.025\ntip_radius: 1.5e-3\ncom_offset: 0.010\ninertia_axial: 5.0e-6\ninertia_transverse: 3.0e-6\n";
  }
  SweepPoint p;
  p.top = top;
  p.patch = PatchRadius{0.0, true};
  try {
    make_sweep_scene(p, settings());
    FAIL() << "hertz accepted for a top without materials";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("--patch-radius = 'hertz'"), std::string::npos) << m;
    EXPECT_NE(m.find("young_modulus"), std::string::npos) << m;
  }
  p.patch = PatchRadius{};
  EXPECT_NO_THROW(make_sweep_scene(p, settings()));  // the same top is fine with the point contact
}

TEST(SweepPatchRadius, CsvColumnIsLast) {
  std::ostringstream header;
  write_sweep_header(header);
  EXPECT_EQ(header.str().substr(header.str().rfind(',') + 1), "patch_radius\n");
  SweepResult r;
  r.point.patch = PatchRadius{0.0, true};
  std::ostringstream row;
  write_sweep_row(row, r);
  EXPECT_EQ(row.str().substr(row.str().rfind(',') + 1), "hertz\n");
  r.point.patch = PatchRadius{};
  row.str("");
  write_sweep_row(row, r);
  EXPECT_EQ(row.str().substr(row.str().rfind(',') + 1), "0\n");
}

}  // namespace
