// `firmament weather` as a user meets it: a short run writes the maps, previews and statistics the
// docs promise (docs/weather.md, "Command line"); bad input exits 2 and names what is wrong.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "astro/time.h"
#include "core/exr_io.h"
#include "core/scene.h"
#include "sky/scene_weather.h"
#include "tests/cli/cli_runner.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

using test::CommandRun;
using test::firmament;

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kSmallGrid = " --set /weather/grid/cells_x=32 --set /weather/grid/cells_y=32";

TEST(CliWeather, ShortRunWritesMapsPreviewsAndStats) {
  auto dir = test::scratchDir("cli_weather");
  auto scene = test::sourceDir() / "scenes" / "fair-weather.json";
  CommandRun r =
      firmament("weather " + scene.string() + " --hours 1 --interval-min 30" + kSmallGrid + " --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;

  // Frames at 0, 30 and 60 min: weather and wind maps (EXR, 32 × 32 RGBA) and a preview (PNG).
  for (const char* frame : {"0000", "0001", "0002"}) {
    for (const char* kind : {"weather_", "wind_"}) {
      auto path = dir / (std::string(kind) + frame + ".exr");
      ASSERT_TRUE(std::filesystem::exists(path)) << path;
      Image image = readExr(path);
      EXPECT_EQ(image.width, 32) << path;
      EXPECT_EQ(image.height, 32) << path;
      EXPECT_EQ(image.channels, 4) << path;
      for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v)) << path;
      EXPECT_FALSE(image.metadata["weather:time_s"].empty()) << path;
    }
    auto png = dir / (std::string("preview_") + frame + ".png");
    ASSERT_TRUE(std::filesystem::exists(png)) << png;
    std::string bytes = readText(png);
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(1, 3), "PNG") << png;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "weather_0003.exr"));

  // stats.csv: the documented header, then a row every 10 min (0 … 60 min), each with 7 numbers.
  std::istringstream csv(readText(dir / "stats.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "time_h,cloud_fraction,mean_top_m,max_top_m,precip_area_fraction,water_total_kg,precip_out_kg");
  std::vector<double> times;
  while (std::getline(csv, line)) {
    if (line.empty()) continue;
    std::vector<double> values;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) values.push_back(std::stod(field));
    ASSERT_EQ(values.size(), 7u) << line;
    for (double v : values) EXPECT_TRUE(std::isfinite(v)) << line;
    EXPECT_GE(values[1], 0.0);
    EXPECT_LE(values[1], 1.0);
    EXPECT_GT(values[5], 0.0) << "the domain holds water";
    times.push_back(values[0]);
  }
  ASSERT_EQ(times.size(), 7u);
  EXPECT_NEAR(times.front(), 0.0, 1e-9);
  EXPECT_NEAR(times.back(), 1.0, 1e-3);

  // stats.svg: a plot with the four series.
  std::string svg = readText(dir / "stats.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("cloud fraction"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);

  // Nothing half-written left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

// One timeline: `weather` starts where the render's simulation does, so its map an hour after the start
// is, bit for bit, the map that the render's clouds read for a scene an hour after that start.
TEST(CliWeather, MapsAreTheRendersAtTheSameTime) {
  auto dir = test::scratchDir("cli_weather_timeline");
  auto scene = test::sourceDir() / "scenes" / "fair-weather.json";
  const std::string start = " --set /weather/start_utc=2026-06-21T06:00:00Z --set /time/utc=2026-06-21T07:00:00Z";
  CommandRun r = firmament("weather " + scene.string() + " --hours 1 --interval-min 60" + kSmallGrid + start +
                           " --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Image map = readExr(dir / "weather_0001.exr");
  EXPECT_EQ(map.metadata.at("weather:start_utc"), "2026-06-21T06:00:00.000Z");

  clearSceneWeatherCache();
  const Scene oneHourIn =
      Scene::load(scene, {"/weather/start_utc=2026-06-21T06:00:00Z", "/time/utc=2026-06-21T07:00:00Z",
                          "/weather/grid/cells_x=32", "/weather/grid/cells_y=32"});
  EXPECT_DOUBLE_EQ(sceneWeatherRunSeconds(oneHourIn), 3600.0);
  const CloudWeatherMap rendered = cloudWeatherMapForScene(oneHourIn);
  ASSERT_EQ(rendered.map.pixels.size(), map.pixels.size());
  size_t differ = 0;
  for (size_t i = 0; i < map.pixels.size(); ++i) differ += rendered.map.pixels[i] != map.pixels[i];
  EXPECT_EQ(differ, 0u) << "of " << map.pixels.size() << " values";
  double coverage = 0.0;
  for (size_t i = 0; i < map.pixels.size(); i += 4) coverage += map.pixels[i];
  EXPECT_GE(coverage, 0.0);

  // Without a start, both start at the local mean solar midnight before the scene's time (7.98 deg E:
  // 31.92 min before midnight UTC), the day's convection up to the scene's time.
  const Scene noStart = Scene::load(scene, {"/time/utc=2026-06-21T13:00:00Z"});
  EXPECT_EQ(astro::formatUtc(sceneWeatherStart(noStart)), "2026-06-20T23:28:04.800Z");
  EXPECT_NEAR(sceneWeatherRunSeconds(noStart), 13.5 * 3600.0 + 115.2, 1e-6);
}

TEST(CliWeather, BadInputExitsTwoWithAClearMessage) {
  auto dir = test::scratchDir("cli_weather_bad");
  auto scene = (test::sourceDir() / "scenes" / "fair-weather.json").string();
  auto out = " --out " + (dir / "out").string();
  struct Case {
    std::string arguments, fragment;
  };
  auto noWeather = dir / "no_weather.json";
  std::ofstream(noWeather) << R"({"location": {"latitude_deg": 46.5}})";
  const std::vector<Case> cases = {
      {"weather " + scene + " --hours 0" + out, "--hours"},
      {"weather " + scene + " --hours 9000" + out, "--hours"},
      {"weather " + scene + " --interval-min 0" + out, "--interval-min"},
      {"weather " + scene + kSmallGrid, "--out"},
      {"weather " + scene + " --set /weather/preset=monsoon" + out, "/weather/preset"},
      {"weather " + scene + " --set /weather/grid/cells_x=2" + out, "/weather/grid/cells_x"},
      {"weather " + scene + " --set /weather/no_such_key=1" + out, "/weather/no_such_key"},
      {"weather " + scene + " --set /weather/start_utc=2026-06-21T14:00:00Z" + out, "is after /time/utc"},
      {"weather " + scene + " --set /weather/start_utc=2026-06-01T00:00:00Z" + out, "at most 7 days"},
      {"weather " + scene + " --set /weather/start_utc=tomorrow" + out, "/weather/start_utc"},
      {"weather " + noWeather.string() + out, "weather"},
      {"weather " + (dir / "missing.json").string() + out, "missing.json"},
      {"weather" + out, ""},
  };
  for (const auto& c : cases) {
    CommandRun r = firmament(c.arguments);
    EXPECT_EQ(r.exitCode, 2) << c.arguments << ": " << r.output;
    EXPECT_NE(r.output.find(c.fragment), std::string::npos) << c.arguments << ": " << r.output;
  }
  // No maps were written by any of them.
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "weather_0000.exr"));
  CommandRun help = firmament("weather --help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.output.find("usage: firmament weather"), std::string::npos) << help.output;
}

// `bench weather --quick` (docs/weather.md, "Error and cost per knob"): the grid and time step against
// a reference run. The reference's own settings are run again as a row: the model is deterministic, so
// that row's errors are exactly 0. Other seeds give other weather (the floor is above 0), the other
// settings give other days (some error above 0), and fair weather on 21 June makes midday cumulus (the
// day's mean cloud fraction between 0.02 and 0.6 in every row).
TEST(CliWeather, BenchQuickRerunsItsReferenceIdenticallyAndMeasuresTheKnobs) {
  auto dir = test::scratchDir("cli_bench_weather");
  CommandRun r = firmament("bench weather --quick --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream csv(dir / "weather_results.csv");
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line.rfind("preset,cells,cell_size_m,time_step_s,reference,default,cpu_s_per_day,", 0), 0u) << line;
  int rows = 0, references = 0;
  double largestError = 0.0;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
    ASSERT_EQ(f.size(), 16u) << line;
    ++rows;
    EXPECT_EQ(f[0], "fair-weather");
    std::vector<double> v;
    for (size_t i = 6; i < f.size(); ++i) {
      v.push_back(std::stod(f[i]));
      ASSERT_TRUE(std::isfinite(v.back()) && v.back() >= 0.0) << line;
    }
    EXPECT_GT(v[0], 0.0) << "CPU time per day: " << line;
    EXPECT_GT(v[1], 0.02) << line;
    EXPECT_LT(v[1], 0.6) << line;
    EXPECT_GT(v[6], 0.0) << "the floor (other seeds): " << line;
    if (f[4] == "1") {
      ++references;
      for (int k = 2; k <= 5; ++k) EXPECT_EQ(v[k], 0.0) << "the reference run again: " << line;
    } else {
      largestError = std::max(largestError, v[2]);
    }
  }
  EXPECT_EQ(rows, 3);  // 64 cells at 60 and 300 s, the reference's 128 cells at 60 s
  EXPECT_EQ(references, 1);
  EXPECT_GT(largestError, 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "weather_report.md"));
}

}  // namespace
}  // namespace firmament
