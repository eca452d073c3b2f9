// `firmament export-vdb` as a user meets it: bad options exit 2 with a message naming the option and
// what is allowed, and write nothing; a scene without clouds writes an empty grid; a small real export
// writes the file and reports its voxels (tests/vdb reads such files back with OpenVDB).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli/cli_runner.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

using test::CommandRun;
using test::firmament;

size_t filesIn(const std::filesystem::path& dir) {
  return size_t(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

TEST(CliExportVdb, BadOptionsExitTwoNameTheOptionAndWriteNothing) {
  const auto dir = test::scratchDir("cli_export_vdb_bad");
  const std::string scene = (test::sourceDir() / "scenes" / "cumulus.json").string();
  const std::string out = (dir / "clouds.vdb").string();
  struct Case {
    std::string arguments;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"--voxel-size 0", {"--voxel-size", "allowed: 1 to 10000 m"}},
      {"--voxel-size fine", {"--voxel-size", "not a number"}},
      {"--region 1,2,3", {"--region", "not 4", "WEST,SOUTH,EAST,NORTH"}},
      {"--region 5000,-100,-5000,100", {"--region", "WEST must be less than EAST"}},
      {"--region -100,a,100,200", {"--region", "'a'", "not a number"}},
      {"--bottom 3000 --top 2000", {"--bottom", "--top", "less than"}},
      {"--voxel-size 1 --region -100000,-100000,100000,100000", {"voxels", "allowed: at most"}},
      {"--threads -1", {"--threads"}},
  };
  for (const Case& c : cases) {
    const CommandRun run = firmament("export-vdb " + scene + " -o " + out + " " + c.arguments);
    EXPECT_EQ(run.exitCode, 2) << c.arguments << "\n" << run.output;
    for (const std::string& f : c.fragments)
      EXPECT_NE(run.output.find(f), std::string::npos) << c.arguments << ": no '" << f << "' in\n" << run.output;
  }
  const CommandRun wrongExtension = firmament("export-vdb " + scene + " -o " + (dir / "clouds.exr").string());
  EXPECT_EQ(wrongExtension.exitCode, 2);
  EXPECT_NE(wrongExtension.output.find(".vdb"), std::string::npos) << wrongExtension.output;
  EXPECT_EQ(filesIn(dir), 0u) << "a refused export left a file";
}

TEST(CliExportVdb, SceneWithoutCloudsWritesAnEmptyGrid) {
  const auto dir = test::scratchDir("cli_export_vdb_empty");
  const auto scene = test::scratchDir("cli_export_vdb_empty_scene") / "clear.json";
  std::ofstream(scene) << R"({"time": {"utc": "2026-06-21T12:00:00Z"}})";
  const CommandRun run =
      firmament("export-vdb " + scene.string() + " -o " + (dir / "empty.vdb").string() + " --voxel-size 1000");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("0 active voxels"), std::string::npos) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "empty.vdb"));
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(CliExportVdb, SmallExportReportsItsVoxels) {
  const auto dir = test::scratchDir("cli_export_vdb_small");
  const CommandRun run =
      firmament("export-vdb " + (test::sourceDir() / "scenes" / "cumulus.json").string() + " -o " +
                (dir / "sub" / "small.vdb").string() + " --voxel-size 250 --region -3000,-3000,3000,3000 --threads 2");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  for (const char* f : {"small.vdb", "grid 'density'", "active voxels of", "max sigma_t", "thread(s)"})
    EXPECT_NE(run.output.find(f), std::string::npos) << "no '" << f << "' in\n" << run.output;
  EXPECT_EQ(run.output.find(" 0 active voxels"), std::string::npos) << run.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "sub" / "small.vdb"));
  EXPECT_GT(std::filesystem::file_size(dir / "sub" / "small.vdb"), 1000u);
  EXPECT_EQ(filesIn(dir / "sub"), 1u) << "a temporary file was left beside the output";
}

}  // namespace
}  // namespace firmament
