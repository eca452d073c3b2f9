// The `firmament` tool as a user meets it: exit codes (0 ok, 2 bad input, 3 runtime), messages that
// name the file and JSON pointer, and the files a render writes.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "core/exr_io.h"
#include "tests/cli/cli_runner.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

using test::CommandRun;
using test::firmament;

std::filesystem::path writeScene(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, HelpAndVersion) {
  EXPECT_EQ(firmament("--version").exitCode, 0);
  CommandRun help = firmament("--help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.output.find("render"), std::string::npos);
  EXPECT_NE(help.output.find("compare"), std::string::npos);
  for (const char* command : {"render", "compare", "check", "sun"}) {
    CommandRun r = firmament(std::string(command) + " --help");
    EXPECT_EQ(r.exitCode, 0) << command;
    EXPECT_NE(r.output.find("usage: firmament"), std::string::npos) << command;
  }
  EXPECT_EQ(firmament("no-such-command").exitCode, 2);
  EXPECT_EQ(firmament("render --no-such-option").exitCode, 2);
}

// Every kind of bad scene file the issue names: exit 2 and a message naming the file and the place.
TEST(Cli, BadScenesExitTwoWithAClearMessage) {
  auto dir = test::scratchDir("cli_bad_scenes");
  struct Case {
    std::string name, text;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"unknown_key.json", R"({"camera": {"fov": 60}})", {"unknown_key.json", "/camera/fov", "unknown key"}},
      {"wrong_type.json", R"({"camera": {"width": "wide"}})", {"wrong_type.json", "/camera/width", "integer"}},
      {"out_of_range.json",
       R"({"clouds": {"layers": [{"bottom_m": -5}]}})",
       {"out_of_range.json", "/clouds/layers/0/bottom_m", "[0, 20000]"}},
      {"malformed.json", "{\"camera\": {", {"malformed.json", "malformed JSON", "line 1"}},
      {"empty.json", "", {"empty.json", "empty"}},
  };
  for (const auto& c : cases) {
    auto path = writeScene(dir, c.name, c.text);
    CommandRun r = firmament("render " + path.string() + " -o " + (dir / "x.exr").string());
    EXPECT_EQ(r.exitCode, 2) << c.name << ": " << r.output;
    for (const auto& f : c.fragments) EXPECT_NE(r.output.find(f), std::string::npos) << c.name << ": " << r.output;
  }
  CommandRun missing = firmament("render " + (dir / "missing.json").string());
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.output.find("missing.json"), std::string::npos);
  CommandRun badSet = firmament("render --set /camera/fov_deg=500 --explain");
  EXPECT_EQ(badSet.exitCode, 2);
  EXPECT_NE(badSet.output.find("/camera/fov_deg"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));  // nothing written on bad input
}

// The clouds' still sub-frames (--still-samples, /clouds/march/still_samples): out of range or not an
// integer is exit 2 naming the knob and the allowed values.
TEST(Cli, BadStillSamplesExitTwoWithTheAllowedValues) {
  for (const char* bad : {"0", "65", "many"}) {
    CommandRun r = firmament(std::string("render --still-samples ") + bad + " --explain");
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("still_samples"), std::string::npos) << r.output;
    if (std::string(bad) != "many") {
      EXPECT_NE(r.output.find("integer in [1, 64]"), std::string::npos) << r.output;
    }
  }
}

// -o SCENE.exr beside SCENE.json would write the render's stats over the scene itself: refused (exit 2,
// naming both files) for render, a sequence's frames and reference; the scene is left as it was.
TEST(Cli, OutputsNeverOverwriteTheScene) {
  auto dir = test::scratchDir("cli_overwrite_scene");
  const std::string text = R"({"camera": {"width": 8, "height": 6}})";
  const auto scene = writeScene(dir, "sky.json", text);
  const auto frame = writeScene(dir, "seq_0001.json", text);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render " + scene.string() + " -o " + (dir / "sky.exr").string(), "sky.json"},
      {"render " + frame.string() + " --frames 2 -o " + (dir / "seq.exr").string(), "seq_0001.json"},
      {"reference " + scene.string() + " --spp 1 -o " + (dir / "sky.exr").string(), "sky.json"},
  };
  for (const auto& [arguments, victim] : cases) {
    CommandRun r = firmament(arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments << ": " << r.output;
    EXPECT_NE(r.output.find("would overwrite the input"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(victim), std::string::npos) << r.output;
  }
  for (const auto& path : {scene, frame}) {
    std::ifstream in(path);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), text) << path;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "sky.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "seq_0000.exr"));
}

// The bench's own options: a wrong scenario or sample count is refused (exit 2, naming the option and
// what is allowed) before any reference is rendered, and nothing is written into the output folder.
TEST(Cli, BenchRefusesBadOptionsBeforeAnyWork) {
  auto dir = test::scratchDir("cli_bench_bad");
  struct Case {
    std::string arguments;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"bench clouds --scenario noon", {"--scenario noon", "cumulus_noon", "stratocumulus_sunset"}},
      {"bench clouds --reference-spp 0", {"--reference-spp", "[1, "}},
      {"bench clouds --calibrate --light-steps 0", {"--light-steps", "[1, 64]"}},
      {"bench clouds --calibrate --phase mie", {"--phase", "mie"}},
      {"bench clouds --calibrate --group nimbus", {"--group nimbus", "cumulonimbus", "stratus"}},
      {"bench clouds --timing-only --images", {"--timing-only", "--images"}},
      {"bench clouds --timing-only --reference-spp 64", {"--timing-only", "--reference-spp"}},
      {"bench clouds --calibrate --timing-only", {"--timing-only", "--calibrate"}},
      {"bench clouds --calibrate --low-sun --reflection-only", {"--low-sun", "--reflection-only"}},
      {"bench clouds --timing-only --timing-size 1920", {"--timing-size 1920", "WxH", "8..8192"}},
      {"bench clouds --timing-only --timing-size 4x4", {"--timing-size 4x4", "WxH"}},
      {"bench clouds --timing-setting quality", {"--timing-setting", "--timing-only"}},
      {"bench clouds --timing-only --error-setting default", {"--error-setting", "--timing-only"}},
      {"bench terrain --scenario cumulus", {"--scenario cumulus", "cumulus_noon", "dem_luxembourg"}},
      {"bench terrain --scenario dem_luxembourg --dem-dir nowhere", {"nowhere", "scripts/fetch_test_dems.sh"}},
      {"bench weather --scenario storm", {"unknown preset 'storm'", "fair-weather", "thunderstorm"}},
      {"bench night --scenario stars_only", {"--scenario stars_only", "moon_disc", "twilight"}},
  };
  for (const auto& c : cases) {
    const auto out = dir / "out";
    CommandRun r = firmament(c.arguments + " --out " + out.string());
    EXPECT_EQ(r.exitCode, 2) << c.arguments << ": " << r.output;
    for (const auto& f : c.fragments) EXPECT_NE(r.output.find(f), std::string::npos) << c.arguments << ": " << r.output;
    EXPECT_TRUE(!std::filesystem::exists(out) || std::filesystem::is_empty(out)) << c.arguments;
  }
}

// --timing-size sets the frame timing's image size (for a lent GPU's 1920x1080 timings): every row of
// clouds_timing.csv names it.
TEST(Cli, BenchCloudTimingTakesItsImageSize) {
  auto dir = test::scratchDir("cli_bench_timing_size");
  // Four rows (the defaults' still and 1/16 sequence, and view_steps 48's): every row takes the size.
  CommandRun r = firmament(
      "bench clouds --timing-only --scenario cirrus --timing-size 40x24 --repeats 1 --timing-setting \"view_steps 48\" "
      "--out " +
      dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream csv(dir / "clouds_timing.csv");
  std::string line;
  std::getline(csv, line);  // header: scenario,setting,width,height,...
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_NE(line.find(",40,24,"), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 4);
}

// The lines of a CSV file after its header.
std::vector<std::string> csvRows(const std::filesystem::path& file) {
  std::ifstream csv(file);
  std::string line;
  std::getline(csv, line);  // header
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  return rows;
}

// --timing-setting times only the rows whose name contains one of its texts, and the defaults' still
// and 1/16 sequence.
TEST(Cli, BenchCloudTimingSettingPicksItsRows) {
  auto dir = test::scratchDir("cli_bench_timing_setting");
  CommandRun r = firmament(
      "bench clouds --timing-only --scenario cirrus --timing-size 40x24 --repeats 1 --timing-setting "
      "\"reflected_light off|quality low (\" --out " +
      dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::vector<std::string> settings;
  for (const std::string& line : csvRows(dir / "clouds_timing.csv")) {
    const size_t open = line.find(",\"") + 2, close = line.find('"', open);
    settings.push_back(line.substr(open, close - open));
  }
  const std::vector<std::string> expected = {"default",
                                             "reflected_light off",
                                             "reflected_light off, temporal_update 16 (sequence)",
                                             "quality low (32v/4l/3o)",
                                             "quality low (32v/4l/3o), temporal_update 16 (sequence)",
                                             "temporal_update 16 (sequence)"};
  EXPECT_EQ(settings, expected);
}

// --error-setting computes only the error rows whose "knob value" contains one of its texts, and the
// default row; no timing sweep follows.
TEST(Cli, BenchCloudErrorSettingPicksItsRows) {
  auto dir = test::scratchDir("cli_bench_error_setting");
  CommandRun r = firmament(
      "bench clouds --quick --scenario cumulus_noon --reference-spp 2 --repeats 1 --error-setting "
      "\"ms_model no diffusion floor|view_steps 256\" --out " +
      dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::vector<std::string> rows;
  for (const std::string& line : csvRows(dir / "clouds_results.csv"))
    rows.push_back(line.substr(0, line.find('"', line.find('"') + 1) + 1));  // knob,"value"
  const std::vector<std::string> expected = {"default,\"64v/6l/3o\"", "ms_model,\"no diffusion floor\"",
                                             "view_steps,\"256\""};
  EXPECT_EQ(rows, expected);
  EXPECT_FALSE(std::filesystem::exists(dir / "clouds_timing.csv"));
}

// The all-order and the first-order references are kept in DIR/references: a second run with the
// same --out reads them (and says so) and gives the same errors; a damaged cache file is rendered again.
TEST(Cli, BenchCloudReusesItsReferences) {
  auto dir = test::scratchDir("cli_bench_reference_cache");
  const std::string command =
      "bench clouds --quick --scenario cumulus_noon --reference-spp 4 --repeats 1 --error-setting "
      "\"view_steps 256|1 octave vs order 1\" --out " +
      dir.string();
  auto errors = [&] {
    std::string all;
    for (const std::string& line : csvRows(dir / "clouds_results.csv")) {
      // knob,"value",scenario,precompute_ms,frame_ms,rel_rmse,...: drop the two times.
      const size_t scenarioEnd = line.find(',', line.find('"', line.find('"') + 1) + 2);
      const size_t framesEnd = line.find(',', line.find(',', scenarioEnd + 1) + 1);
      all += line.substr(0, scenarioEnd) + line.substr(framesEnd) + "\n";
    }
    return all;
  };
  CommandRun first = firmament(command);
  ASSERT_EQ(first.exitCode, 0) << first.output;
  EXPECT_EQ(first.output.find("paths/pixel from"), std::string::npos) << first.output;
  const std::string firstErrors = errors();
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "references"))
    files += entry.path().extension() == ".exr";
  EXPECT_EQ(files, 4);  // image and luminance, all orders and the first

  CommandRun second = firmament(command);
  ASSERT_EQ(second.exitCode, 0) << second.output;
  EXPECT_NE(second.output.find("paths/pixel from"), std::string::npos) << second.output;
  EXPECT_EQ(errors(), firstErrors);

  // Damaged: every file of the cache truncated; the run renders the reference again and overwrites them.
  for (const auto& entry : std::filesystem::directory_iterator(dir / "references"))
    std::filesystem::resize_file(entry.path(), 10);
  CommandRun third = firmament(command);
  ASSERT_EQ(third.exitCode, 0) << third.output;
  EXPECT_EQ(third.output.find("paths/pixel from"), std::string::npos) << third.output;
  EXPECT_EQ(errors(), firstErrors);
}

TEST(Cli, RenderWritesExrPngAndStats) {
  auto dir = test::scratchDir("cli_render");
  auto scene = test::sourceDir() / "scenes" / "default.json";
  CommandRun r = firmament("render " + scene.string() + " --width 40 --height 24 -o " + (dir / "sky.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "sky.exr"));
  EXPECT_TRUE(std::filesystem::exists(dir / "sky.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "sky.json"));
  Image image = readExr(dir / "sky.exr");
  EXPECT_EQ(image.width, 40);
  EXPECT_EQ(image.height, 24);
  EXPECT_FALSE(image.metadata["firmament.device"].empty());
  EXPECT_FALSE(image.metadata["firmament.scene_hash"].empty());
  for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  // No temporary files left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();

  // compare: identical images -> exit 0 and an infinite PSNR.
  CommandRun same = firmament("compare " + (dir / "sky.exr").string() + " " + (dir / "sky.exr").string());
  EXPECT_EQ(same.exitCode, 0) << same.output;
  CommandRun mismatch = firmament("compare " + (dir / "sky.exr").string() + " " + (dir / "nope.exr").string());
  EXPECT_EQ(mismatch.exitCode, 2);
}

// A sequence: one EXR per frame, the clouds of every frame after the first reprojected (the stats say
// so); rates that leave the allowed camera range, or rates without --frames, exit 2 before writing.
TEST(Cli, RenderFramesWritesASequence) {
  auto dir = test::scratchDir("cli_frames");
  const std::string scene = writeScene(dir, "clouds.json", R"({"camera": {"width": 32, "height": 18, "pitch_deg": 30},
      "clouds": {"layers": [{"kind": "cumulus", "bottom_m": 1500, "top_m": 3000, "coverage": 0.6}], "wind_m_s": 10}})")
                                .string();
  CommandRun r = firmament("render " + scene + " --frames 3 --yaw-rate 6 -o " + (dir / "seq.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (int i = 0; i < 3; ++i) {
    const std::string stem = "seq_000" + std::to_string(i);
    ASSERT_TRUE(std::filesystem::exists(dir / (stem + ".exr"))) << stem;
    std::ifstream stats(dir / (stem + ".json"));
    const std::string text((std::istreambuf_iterator<char>(stats)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(i == 0 ? "\"reprojected\": false" : "\"reprojected\": true"), std::string::npos)
        << stem << text;
    Image image = readExr(dir / (stem + ".exr"));
    for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "seq.exr"));
  // Without a sun section the sun follows the clock: a 10-minute time-lapse moves it (~1.7 deg here).
  CommandRun lapse =
      firmament("render " + scene + " --frames 2 --frame-interval 600 -o " + (dir / "lapse.exr").string());
  ASSERT_EQ(lapse.exitCode, 0) << lapse.output;
  double zenith[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    std::ifstream stats(dir / ("lapse_000" + std::to_string(i) + ".json"));
    zenith[i] = nlohmann::json::parse(stats).at("sun").at("zenith_deg").get<double>();
  }
  EXPECT_GT(std::abs(zenith[1] - zenith[0]), 0.5) << zenith[0] << " " << zenith[1];
  EXPECT_LT(std::abs(zenith[1] - zenith[0]), 5.0) << zenith[0] << " " << zenith[1];
  for (const std::string& bad :
       {std::string("--frames 0"), std::string("--yaw-rate 5"), std::string("--frames 40 --pitch-rate 200")}) {
    CommandRun b = firmament("render " + scene + " " + bad + " -o " + (dir / "bad.exr").string());
    EXPECT_EQ(b.exitCode, 2) << bad << ": " << b.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr")) << bad;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad_0000.exr")) << bad;
  }
}

// The cloud noise on disk (docs/clouds/noise-and-density.md): a second `render` of a cloud scene reads the noise
// that the first baked (stats JSON clouds.noise) and writes the same image, bit for bit. The cache
// folder is a scratch one (FIRMAMENT_CACHE_DIR), so the test starts empty and leaves the user's alone.
TEST(Cli, RenderReadsTheCloudNoiseTheLastRunBaked) {
  auto dir = test::scratchDir("cli_noise_cache");
  const std::string scene = writeScene(dir, "clouds.json", R"({"camera": {"width": 24, "height": 14, "pitch_deg": 30},
      "clouds": {"layers": [{"kind": "cumulus", "bottom_m": 1500, "top_m": 3000, "coverage": 0.6}], "seed": 4242}})")
                                .string();
  const char* saved = std::getenv("FIRMAMENT_CACHE_DIR");
  const std::string previous = saved ? saved : "";
  setenv("FIRMAMENT_CACHE_DIR", (dir / "cache").c_str(), 1);
  std::string source[2];
  for (int i = 0; i < 2; ++i) {
    CommandRun r = firmament("render " + scene + " -o " + (dir / ("run" + std::to_string(i) + ".exr")).string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream stats(dir / ("run" + std::to_string(i) + ".json"));
    source[i] = nlohmann::json::parse(stats).at("clouds").at("noise").get<std::string>();
  }
  if (saved)
    setenv("FIRMAMENT_CACHE_DIR", previous.c_str(), 1);
  else
    unsetenv("FIRMAMENT_CACHE_DIR");
  EXPECT_EQ(source[0], "baked");
  EXPECT_EQ(source[1], "disk cache");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "cache" / "noise"))
    files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
  EXPECT_EQ(readExr(dir / "run0.exr").pixels, readExr(dir / "run1.exr").pixels);
}

TEST(Cli, ExplainListsOnlyNeededPasses) {
  // The default scene is a landscape under cumulus: it needs the cloud and terrain passes.
  CommandRun full = firmament("render --explain");
  ASSERT_EQ(full.exitCode, 0) << full.output;
  EXPECT_NE(full.output.find("clouds/render_clouds"), std::string::npos);
  EXPECT_NE(full.output.find("terrain/cast_terrain"), std::string::npos);
  // A clear daytime sky over no terrain runs neither, nor the night sky.
  auto dir = test::scratchDir("cli_explain");
  const std::string clear = writeScene(dir, "clear.json", R"({"camera": {"width": 32, "height": 16}})").string();
  CommandRun r = firmament("render " + clear + " --explain");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::size_t leftOut = r.output.find("left out:");
  ASSERT_NE(leftOut, std::string::npos) << r.output;
  // The passes' lines only: the first line names the scene file, whose path may hold any word.
  const std::size_t firstLineEnd = r.output.find('\n');
  ASSERT_LT(firstLineEnd, leftOut) << r.output;
  const std::string passes = r.output.substr(firstLineEnd, leftOut - firstLineEnd);
  EXPECT_NE(passes.find("sky/render_sky"), std::string::npos);
  EXPECT_EQ(passes.find("clouds/"), std::string::npos);
  EXPECT_EQ(passes.find("terrain/"), std::string::npos);
  EXPECT_EQ(passes.find("night/"), std::string::npos);
  EXPECT_EQ(passes.find("aerial_perspective_volume"), std::string::npos);
  // What was left out says why.
  EXPECT_NE(r.output.find("the night runs below 10 deg", leftOut), std::string::npos) << r.output;
}

}  // namespace
}  // namespace firmament
