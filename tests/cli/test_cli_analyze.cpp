// `firmament analyze clouds` as a user meets it: a small analysis of a weather scene writes stats.json,
// clouds.csv, optical_depth.exr and mask.png that agree with each other; bad input exits 2, names what
// is wrong and writes nothing (docs/clouds/shapes.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/exr_io.h"
#include "core/png_io.h"
#include "tests/cli/cli_runner.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

namespace fs = std::filesystem;
using test::CommandRun;
using test::firmament;

TEST(CliAnalyzeClouds, WeatherSceneWritesStatisticsThatAgreeWithTheFields) {
  const fs::path dir = test::scratchDir("cli_analyze_clouds");
  const std::string scene = (test::sourceDir() / "scenes" / "cumulus.json").string();
  const CommandRun run = firmament("analyze clouds " + scene +
                                   " --region -4000,-3000,4000,3000 --pixel-size 100 --out " + (dir / "out").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::ifstream in(dir / "out" / "stats.json");
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json stats = nlohmann::json::parse(text.str());
  EXPECT_EQ(stats["columns"][0], 80);
  EXPECT_EQ(stats["columns"][1], 60);

  // The fraction is the mask's share of white pixels; the mask is the optical depth above the threshold.
  const ExrChannel depth = readExrChannel(dir / "out" / "optical_depth.exr", {"Y"});
  const Image8 mask = readPng(dir / "out" / "mask.png");
  ASSERT_EQ(depth.width, 80);
  ASSERT_EQ(mask.width, 80);
  size_t cloudy = 0;
  for (size_t p = 0; p < depth.values.size(); ++p) {
    EXPECT_GE(depth.values[p], 0.0f);
    EXPECT_EQ(mask.pixels[p] == 255, depth.values[p] > 1.0f) << "pixel " << p;
    cloudy += depth.values[p] > 1.0f;
  }
  EXPECT_DOUBLE_EQ(stats["cloud_fraction"].get<double>(), double(cloudy) / double(depth.values.size()));
  EXPECT_GT(cloudy, 0u) << "the cumulus scene has cloud over the camera's 8 x 6 km";
  // The map's coverage (CloudMedium::mapCoverage): cloud is asked where the field has some.
  const double asked = stats["map_coverage"].get<double>();
  EXPECT_GT(asked, 0.0);
  EXPECT_LE(asked, 1.0);

  // clouds.csv: one row per cloud, whose areas add up to the cloudy columns' area.
  std::ifstream csv(dir / "out" / "clouds.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "area_m2,perimeter_m,size_m,top_m,touches_edge");
  int rows = 0;
  double area = 0.0;
  while (std::getline(csv, line)) {
    ++rows;
    area += std::stod(line.substr(0, line.find(',')));
  }
  EXPECT_EQ(rows, stats["clouds"].get<int>());
  EXPECT_NEAR(area, double(cloudy) * 100.0 * 100.0, 1e-6 * area + 1.0);
  const double top = stats["cloud_top_m"]["max"].get<double>();
  EXPECT_GT(top, 500.0);
  EXPECT_LT(top, 6000.0);
}

TEST(CliAnalyzeClouds, BadInputExitsTwoNamingWhatIsWrongAndWritesNothing) {
  const fs::path dir = test::scratchDir("cli_analyze_clouds_bad");
  const std::string cumulus = (test::sourceDir() / "scenes" / "cumulus.json").string();
  const std::string out = " --out " + (dir / "out").string();
  std::ofstream(dir / "no_clouds.json") << R"({"time": {"utc": "2026-06-21T12:00:00Z"}})";
  struct Case {
    std::string arguments;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"analyze rain " + cumulus + out, {"'rain'", "allowed: clouds"}},
      {"analyze clouds " + cumulus, {"--out"}},
      {"analyze clouds " + cumulus + out + " --pixel-size 1", {"--pixel-size", "allowed: 10 to 5000 m"}},
      {"analyze clouds " + cumulus + out + " --tau 0", {"--tau", "allowed"}},
      {"analyze clouds " + cumulus + out + " --region 1,2,3", {"--region", "not 4"}},
      {"analyze clouds " + cumulus + out + " --pixel-size 10 --region -100000,-100000,100000,100000",
       {"columns", "at most"}},
      {"analyze clouds " + (dir / "no_clouds.json").string() + out, {"no cloud layers"}},
  };
  for (const Case& c : cases) {
    const CommandRun run = firmament(c.arguments);
    EXPECT_EQ(run.exitCode, 2) << c.arguments << "\n" << run.output;
    for (const std::string& f : c.fragments)
      EXPECT_NE(run.output.find(f), std::string::npos) << c.arguments << ": no '" << f << "' in\n" << run.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out")) << "a refused analysis created its folder";
}

}  // namespace
}  // namespace firmament
