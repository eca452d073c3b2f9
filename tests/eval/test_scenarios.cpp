// The benchmark and calibration scenarios are scene files (eval/scenarios/<group>/*.json) listed in each
// group's index.json: every file is a valid scene, every index entry has its file and every file its
// entry, and the benches read the lists the index gives.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "eval/atmosphere_bench.h"
#include "eval/scenarios.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

const char* const kGroups[] = {"atmosphere", "clouds", "calibration", "terrain"};

TEST(EvalScenarios, EveryIndexEntryIsAValidSceneFileAndEveryFileIsListed) {
  std::set<std::string> listed;
  for (const char* group : kGroups) {
    const nlohmann::json index = evalScenarioIndex(group);
    ASSERT_TRUE(index.contains("scenarios")) << group;
    EXPECT_GE(index.at("scenarios").size(), 5u) << group;
    for (const nlohmann::json& entry : index.at("scenarios")) {
      const std::string name = entry.at("name").get<std::string>();
      EXPECT_FALSE(entry.at("description").get<std::string>().empty()) << group << "/" << name;
      EXPECT_TRUE(listed.insert(std::string(group) + "/" + name + ".json").second) << "listed twice: " << name;
      const Scene scene = evalScenarioScene(group, name);
      EXPECT_EQ(scene.source(), "eval/scenarios/" + std::string(group) + "/" + name + ".json");
      EXPECT_GT(scene.integer("/camera/width"), 0);
      if (std::string(group) == "terrain") {
        EXPECT_TRUE(scene.hasSection("terrain")) << name;  // the ground against its reference
      } else if (std::string(group) != "atmosphere") {
        EXPECT_TRUE(scene.hasSection("clouds")) << name;
      } else {
        EXPECT_FALSE(scene.hasSection("clouds")) << name;  // clear skies against the spectral reference
      }
    }
    listed.insert(std::string(group) + "/index.json");
  }
  for (const std::string& path : evalScenarioPaths()) EXPECT_TRUE(listed.count(path)) << "not in an index: " << path;
  EXPECT_EQ(listed.size(), evalScenarioPaths().size());
}

TEST(EvalScenarios, BuiltInFilesAreTheSourceTreesFiles) {
  // The program carries the files as they are in the tree (rebuilt when one changes).
  for (const std::string& path : evalScenarioPaths()) {
    std::ifstream in(test::sourceDir() / "eval/scenarios" / path);
    ASSERT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), evalScenarioText(path)) << path;
  }
  EXPECT_THROW(evalScenarioText("clouds/no_such_scenario.json"), std::logic_error);
}

TEST(EvalScenarios, AtmosphereBenchTakesSizesAndPathsFromTheIndex) {
  const std::vector<BenchScenario> full = atmosphereBenchScenarios(false), quick = atmosphereBenchScenarios(true);
  ASSERT_EQ(full.size(), evalScenarioIndex("atmosphere").at("scenarios").size());
  ASSERT_EQ(quick.size(), full.size());
  for (size_t i = 0; i < full.size(); ++i) {
    const Scene scene = benchScenarioScene(full[i]);
    EXPECT_EQ(scene.integer("/camera/width"), full[i].width);
    EXPECT_GE(full[i].referenceSamples, quick[i].referenceSamples) << full[i].name;
    EXPECT_LE(quick[i].width, full[i].width) << full[i].name;
  }
}

}  // namespace
}  // namespace firmament
