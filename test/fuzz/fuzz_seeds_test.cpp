// Replays every file of test/fuzz/corpus/<target>/ through its fuzz target (fuzz_targets.hpp): the seeds and the
// regression inputs of past findings run in every build, the sanitized one included.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;
using Target = std::string (*)(const std::uint8_t*, std::size_t);

std::vector<fs::path> corpus(const std::string& target) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(TOP_SIM_FUZZ_CORPUS_DIR) / target))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void replay(const std::string& name, Target target) {
  const std::vector<fs::path> files = corpus(name);
  ASSERT_FALSE(files.empty()) << "no seeds in " << TOP_SIM_FUZZ_CORPUS_DIR << "/" << name;
  for (const fs::path& file : files) {
    const std::vector<std::uint8_t> data = bytes_of(file);
    EXPECT_EQ(target(data.data(), data.size()), "") << file;
  }
}

TEST(FuzzSeeds, SceneSeedsAreRefusedWithAMessageOrRunFiniteOrToANamedFault) {
  replay("scene_loader", top_sim::fuzz::scene_loader);
}
// The command and step targets start from every shipped scene: a scene added to config/scenes must join their list.
TEST(FuzzSeeds, CommandAndStepTargetsDrawFromEveryShippedScene) {
  const std::vector<std::string> listed = top_sim::fuzz::scene_files();
  for (const auto& entry : fs::directory_iterator(fs::path(TOP_SIM_FUZZ_CONFIG_DIR) / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().stem().string();
    EXPECT_NE(std::find(listed.begin(), listed.end(), name), listed.end())
        << name << ".yaml is not in kSceneFiles of test/fuzz/fuzz_targets.cpp";
  }
}

TEST(FuzzSeeds, CommandSeedsAreAppliedAsValidatedOrRefusedWithoutEffect) { replay("command", top_sim::fuzz::command); }
TEST(FuzzSeeds, StepSeedsStepToAFiniteStateOrANamedFault) { replay("step", top_sim::fuzz::step); }

}  // namespace
