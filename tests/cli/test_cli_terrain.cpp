// `firmament terrain` as a user meets it: a procedural and a GDAL scene write heights.exr,
// hillshade.png and terrain.json (docs/terrain.md, "Command line"); every bad input exits 2 and names
// what is wrong.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

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

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return nlohmann::json::parse(s.str());
}

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(CliTerrain, ProceduralSceneWritesHeightsHillshadeAndReport) {
  const fs::path dir = test::scratchDir("cli_terrain_procedural");
  writeText(dir / "scene.json", R"({"terrain": {"style": "hills", "extent_m": 3000, "resolution": 97}})");
  const CommandRun run = firmament("terrain " + (dir / "scene.json").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(dir / "out" / "terrain.json");
  EXPECT_EQ(report["kind"], "procedural");
  EXPECT_EQ(report["style"], "hills");
  EXPECT_EQ(report["samples"][0], 97);
  EXPECT_DOUBLE_EQ(report["spacing_m"][0].get<double>(), 3000.0 / 96.0);
  const ExrChannel heights = readExrChannel(dir / "out" / "heights.exr", {"Y"});
  EXPECT_EQ(heights.width, 97);
  float lo = 1e30f, hi = -1e30f;
  for (float h : heights.values) {
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  EXPECT_EQ(double(lo), report["min_height_m"].get<double>());
  EXPECT_EQ(double(hi), report["max_height_m"].get<double>());
  const Image8 preview = readPng(dir / "out" / "hillshade.png");
  EXPECT_EQ(preview.width, 97);
  EXPECT_EQ(preview.channels, 3);
}

TEST(CliTerrain, GdalSceneOnARealDemReportsItsDataShare) {
  const fs::path dem = fs::path(FIRMAMENT_TEST_DEM_DIR) / "stars" / "olinda_dem_utm25s.tif";
  ASSERT_TRUE(fs::exists(dem)) << dem << " is missing: run scripts/fetch_test_dems.sh " << FIRMAMENT_TEST_DEM_DIR;
  const fs::path dir = test::scratchDir("cli_terrain_gdal");
  // Olinda, Brazil: 7.99° S, 34.85° W lies on the raster.
  writeText(dir / "scene.json", R"({"location": {"latitude_deg": -8.0, "longitude_deg": -34.86, "height_m": 20},
    "terrain": {"kind": "gdal", "file": ")" +
                                    dem.string() + R"(", "extent_m": 20000, "resolution": 101}})");
  const CommandRun run = firmament("terrain " + (dir / "scene.json").string() + " -o " + (dir / "out").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(dir / "out" / "terrain.json");
  EXPECT_EQ(report["kind"], "gdal");
  // The raster is 111 pixels of 90 m: 10 km of the 20 km square, a quarter of its samples.
  EXPECT_GT(report["data_fraction"].get<double>(), 0.2);
  EXPECT_LT(report["data_fraction"].get<double>(), 0.26);
  EXPECT_LE(report["max_height_m"].get<double>(), 88.0 + 1e-3);
  EXPECT_NE(report["source"].get<std::string>().find("UTM"), std::string::npos);
}

// The shipped DEM scene (scenes/dem-luxembourg.json, the terra package's elev.tif, fetched by
// scripts/fetch_test_dems.sh: CTest's terrain_dems fixture) resolves: most of its 40 km square from the
// raster (95 x 90 pixels over ~70 x 75 km, heights 141-547 m), the rest the procedural fallback.
TEST(CliTerrain, DemSceneResolvesTheTerraDem) {
  const fs::path dir = test::scratchDir("cli_terrain_dem_scene");
  const fs::path dem = fs::path(FIRMAMENT_TEST_DEM_DIR) / "terra" / "elev.tif";
  ASSERT_TRUE(fs::exists(dem)) << dem << " is missing: run scripts/fetch_test_dems.sh " << FIRMAMENT_TEST_DEM_DIR;
  const CommandRun run = firmament("terrain " + (test::sourceDir() / "scenes" / "dem-luxembourg.json").string() +
                                   " --set /terrain/file=" + dem.string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::ifstream in(dir / "out" / "terrain.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_GT(report.at("data_fraction").get<double>(), 0.8);
  EXPECT_GT(report.at("min_height_m").get<double>(), 100.0);
  EXPECT_LT(report.at("max_height_m").get<double>(), 600.0);
}

TEST(CliTerrain, BadInputExitsTwoAndSaysWhy) {
  const fs::path dir = test::scratchDir("cli_terrain_bad");
  writeText(dir / "none.json", "{}");
  writeText(dir / "missing.json", R"({"terrain": {"kind": "gdal", "file": "nowhere.tif"}})");
  writeText(dir / "notes.txt", "not a raster\n");
  writeText(dir / "text.json", R"({"terrain": {"kind": "gdal", "file": "notes.txt"}})");
  writeText(dir / "style.json", R"({"terrain": {"style": "lunar"}})");
  const fs::path dem = fs::path(FIRMAMENT_TEST_DEM_DIR) / "terra" / "elev.tif";
  writeText(dir / "away.json", R"({"terrain": {"kind": "gdal", "file": ")" + dem.string() + "\"}}");
  struct Case {
    std::string arguments, expected;
  } cases[] = {
      {"none.json", "no \"terrain\" section"},
      {"missing.json", "no such raster file"},
      {"text.json", "not a raster GDAL reads"},
      {"style.json", "/terrain/style"},
      {"away.json", "does not cover the scene"},
      {"none.json --set /terrain/vertical_scale=4 --set /location/height_m=7000 --set /terrain/resolution=64",
       "outside the allowed [-11000, 9000]"},
      {"missing.json --set /terrain/kind=heightmap --set /terrain/file=notes.txt", "must be a .png"},
  };
  for (const Case& c : cases) {
    const CommandRun run = firmament("terrain " + (dir / c.arguments).string() + " --out " + (dir / "out").string());
    EXPECT_EQ(run.exitCode, 2) << c.arguments << ": " << run.output;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.arguments << ": " << run.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out" / "terrain.json"));
}

}  // namespace
}  // namespace firmament
