// `firmament timelapse` as a user meets it: a short run at a tiny size (6 frames of 64x36) written as EXR,
// PNG, records, frames.csv and an MP4; the same run killed with SIGKILL and resumed, and the same run in two
// shards (one of them from the Slurm array variables) and --assemble, each giving the uninterrupted run's
// EXR and PNG files byte for byte; a missing ffmpeg; and the refusals of bad input (exit 2, nothing written).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_runner.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

namespace fs = std::filesystem;
using test::CommandRun;
using test::firmament;

constexpr int kFrames = 6;  // 10:00 to 10:25 UTC, one frame per 5 simulated minutes

std::string bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The tool with `environment` ("NAME=VALUE ...") added to its environment.
CommandRun firmamentWith(const std::string& environment, const std::string& arguments) {
  const std::string command = "env " + environment + " " + FIRMAMENT_EXE + " " + arguments + " 2>&1";
  CommandRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) run.output.append(buffer, n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string frame(int i, const char* extension) {
  char name[40];
  std::snprintf(name, sizeof(name), "frame_%06d.%s", i, extension);
  return name;
}

class Timelapse : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = test::scratchDir("timelapse");
    std::ofstream(root_ / "path.json") << R"({"keys": [{"time_s": 0, "yaw_deg": 240, "pitch_deg": 8},
        {"time_s": 1500, "yaw_deg": 270, "pitch_deg": 12, "fov_deg": 70}]})";
    reference_ = firmament(run(root_ / "reference"));
  }
  // The run every test renders, into `dir`, with `extra` options.
  static std::string run(const fs::path& dir, const std::string& extra = "") {
    return "timelapse " + (test::sourceDir() / "scenes/fair-weather.json").string() +
           " --from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --fps 1 --speed 300 --width 64 --height 36"
           " --camera-path " +
           (root_ / "path.json").string() + " --out " + dir.string() + " " + extra;
  }
  // Every frame's EXR and PNG in `dir` equal the uninterrupted run's, byte for byte.
  static void expectFramesOfTheReference(const fs::path& dir) {
    for (int i = 0; i < kFrames; ++i)
      for (const char* extension : {"exr", "png"}) {
        ASSERT_TRUE(fs::exists(dir / frame(i, extension))) << dir / frame(i, extension);
        EXPECT_TRUE(bytes(dir / frame(i, extension)) == bytes(root_ / "reference" / frame(i, extension)))
            << dir / frame(i, extension) << " differs from the uninterrupted run's";
      }
  }
  static inline fs::path root_;
  static inline CommandRun reference_;
};

// The uninterrupted run: every frame's files, a CSV row per frame, the camera on its path, an MP4 whose
// index (moov) comes before its data (+faststart), no partial video left.
TEST_F(Timelapse, RunWritesFramesRecordsCsvAndVideo) {
  ASSERT_EQ(reference_.exitCode, 0) << reference_.output;
  const fs::path dir = root_ / "reference";
  for (int i = 0; i < kFrames; ++i)
    for (const char* extension : {"exr", "png", "json"}) EXPECT_TRUE(fs::exists(dir / frame(i, extension)));
  EXPECT_FALSE(fs::exists(dir / frame(kFrames, "exr")));
  std::ifstream csv(dir / "frames.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, kFrames + 1);  // the header and one row per frame
  // The camera path: the keys' poses at their times, between them in between (yaw 240 -> 270 over 1500 s).
  auto record = [&](int i) { return nlohmann::json::parse(bytes(dir / frame(i, "json"))); };
  EXPECT_NEAR(record(0)["camera"]["yaw_deg"].get<double>(), 240.0, 1e-9);
  EXPECT_NEAR(record(5)["camera"]["yaw_deg"].get<double>(), 270.0, 1e-9);
  EXPECT_NEAR(record(5)["camera"]["fov_deg"].get<double>(), 70.0, 1e-9);
  const double middle = record(2)["camera"]["yaw_deg"].get<double>();
  EXPECT_GT(middle, 245.0);
  EXPECT_LT(middle, 265.0);
  // The clock: the sun moves (about 1.2 deg of altitude in 25 minutes of a June morning at 46.5 N).
  EXPECT_GT(record(5)["sun_altitude_deg"].get<double>() - record(0)["sun_altitude_deg"].get<double>(), 0.5);
  const std::string mp4 = bytes(dir / "timelapse.mp4");
  ASSERT_GT(mp4.size(), 1000u);
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  ASSERT_NE(mp4.find("moov"), std::string::npos);
  ASSERT_NE(mp4.find("mdat"), std::string::npos);
  EXPECT_LT(mp4.find("moov"), mp4.find("mdat")) << "+faststart puts the index first";
  EXPECT_FALSE(fs::exists(dir / "timelapse.partial.mp4"));
}

// Killed with SIGKILL after its third frame, then resumed: the same files as the uninterrupted run, and
// what a killed writer left (a hidden temporary) removed.
TEST_F(Timelapse, ResumeAfterKillGivesTheUninterruptedFrames) {
  ASSERT_EQ(reference_.exitCode, 0) << reference_.output;
  const fs::path dir = root_ / "killed";
  fs::remove_all(dir);
  const std::string command = std::string(FIRMAMENT_EXE) + " " + run(dir, "--no-video") + " >/dev/null 2>&1";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    setpgid(0, 0);
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(dir / frame(2, "json")) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before the kill";
  ASSERT_TRUE(fs::exists(dir / frame(2, "json")));
  ASSERT_FALSE(fs::exists(dir / frame(kFrames - 1, "json"))) << "the kill came after the last frame";
  std::ofstream(dir / ".frame_000004.tmp-999999-0.exr") << "half";
  CommandRun resumed = firmament(run(dir, "--resume"));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(dir / ".frame_000004.tmp-999999-0.exr"));
  expectFramesOfTheReference(dir);
  EXPECT_TRUE(fs::exists(dir / "timelapse.mp4"));
}

// Two shards, the second (from the Slurm array variables) run first so that its PNGs wait for --assemble;
// --assemble without ffmpeg exits 3 and leaves no video; with it, the frames are the single run's.
TEST_F(Timelapse, ShardsAndAssembleGiveTheSingleRunsFrames) {
  ASSERT_EQ(reference_.exitCode, 0) << reference_.output;
  const fs::path dir = root_ / "sharded";
  fs::remove_all(dir);
  CommandRun last = firmamentWith("SLURM_ARRAY_TASK_ID=4 SLURM_ARRAY_TASK_MIN=3 SLURM_ARRAY_TASK_COUNT=2", run(dir));
  ASSERT_EQ(last.exitCode, 0) << last.output;
  EXPECT_NE(last.output.find("Slurm array task 1/2"), std::string::npos) << last.output;
  EXPECT_FALSE(fs::exists(dir / frame(0, "json")));
  EXPECT_TRUE(fs::exists(dir / frame(3, "exr")));
  EXPECT_FALSE(fs::exists(dir / frame(3, "png"))) << "without frames 0-2's records the PNG waits for --assemble";
  EXPECT_FALSE(fs::exists(dir / "frames.csv"));
  CommandRun early = firmament("timelapse --assemble " + dir.string());
  EXPECT_EQ(early.exitCode, 2) << early.output;
  EXPECT_NE(early.output.find("3 of 6 frames are missing"), std::string::npos) << early.output;
  CommandRun first = firmament(run(dir, "--shard 0/2"));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  CommandRun noFfmpeg = firmamentWith("FIRMAMENT_FFMPEG=/nonexistent/ffmpeg", "timelapse --assemble " + dir.string());
  EXPECT_EQ(noFfmpeg.exitCode, 3) << noFfmpeg.output;
  EXPECT_NE(noFfmpeg.output.find("ffmpeg not found"), std::string::npos) << noFfmpeg.output;
  EXPECT_FALSE(fs::exists(dir / "timelapse.mp4"));
  EXPECT_FALSE(fs::exists(dir / "timelapse.partial.mp4"));
  expectFramesOfTheReference(dir);  // the frames and the PNGs are complete without the video
  CommandRun assembled = firmament("timelapse --assemble " + dir.string() + " --codec h265");
  ASSERT_EQ(assembled.exitCode, 0) << assembled.output;
  EXPECT_GT(bytes(dir / "timelapse.mp4").size(), 1000u);
  EXPECT_FALSE(fs::exists(dir / "timelapse.partial.mp4"));
}

// Bad input: exit 2 with a message naming the option, and no folder created; a folder of another scene or
// other options is refused and left as it was.
TEST_F(Timelapse, BadInputExitsTwoAndWritesNothing) {
  ASSERT_EQ(reference_.exitCode, 0) << reference_.output;
  const fs::path fresh = root_ / "never";
  std::ofstream(root_ / "a-file") << "x";
  std::ofstream(root_ / "bad-path.json") << R"({"keys": [{"time_s": 10, "yaw_deg": 0, "pitch_deg": 0},
      {"time_s": 5, "yaw_deg": 0, "pitch_deg": 0}]})";
  const std::string scene = (test::sourceDir() / "scenes/fair-weather.json").string();
  const std::string tail = " --fps 1 --speed 300 --height 36 --out " + fresh.string();
  struct Case {
    std::string arguments, says;
  };
  const Case cases[] = {
      {"--from 2026-13-01T00:00:00Z --to 2026-12-01T00:00:00Z --width 64" + tail, "--from"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T09:00:00Z --width 64" + tail, "is not after"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --frames 4-2", "--frames 4-2"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --frames 0-6", "0 to 5"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --shard 2/2", "--shard 2/2"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --shard one/2", "--shard one/2"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 63" + tail, "even"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --codec vp9", "--codec"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --resume", "holds no time-lapse"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --width 64" + tail + " --camera-path " +
           (root_ / "bad-path.json").string(),
       "/keys/1/time_s"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-21T10:25:00Z --out " + (root_ / "a-file" / "sub").string(), "--out"},
      {"--from 2026-06-21T10:00:00Z --to 2026-06-29T10:00:00Z --width 64" + tail, "at most 7 days"},
  };
  for (const Case& c : cases) {
    CommandRun r = firmament("timelapse " + scene + " " + c.arguments);
    EXPECT_EQ(r.exitCode, 2) << c.arguments << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.arguments << ": " << r.output;
    EXPECT_FALSE(fs::exists(fresh)) << c.arguments;
  }
  // The reference's folder with another scene, or other options: refused, its manifest unchanged.
  const std::string manifest = bytes(root_ / "reference" / "timelapse.json");
  CommandRun otherScene = firmament(run(root_ / "reference", "--set /camera/exposure/compensation_ev=1"));
  EXPECT_EQ(otherScene.exitCode, 2) << otherScene.output;
  EXPECT_NE(otherScene.output.find("another scene"), std::string::npos) << otherScene.output;
  std::string otherOptions = run(root_ / "reference");
  otherOptions.replace(otherOptions.find("--speed 300"), 11, "--speed 150");
  CommandRun otherSpeed = firmament(otherOptions);
  EXPECT_EQ(otherSpeed.exitCode, 2) << otherSpeed.output;
  EXPECT_NE(otherSpeed.output.find("other options (speed"), std::string::npos) << otherSpeed.output;
  EXPECT_EQ(bytes(root_ / "reference" / "timelapse.json"), manifest);
}

// A time-lapse through the local solar midnight (7.98 deg E: 23:28:04.8 UTC) runs one weather simulation
// on through it: the frame after midnight continues the run from the midnight before the first frame
// (24.5 h long), instead of starting the day again (0.5 h).
TEST_F(Timelapse, WeatherRunsOnThroughTheSolarMidnight) {
  const fs::path dir = root_ / "midnight";
  const CommandRun r =
      firmament("timelapse " + (test::sourceDir() / "scenes/fair-weather.json").string() +
                " --from 2026-06-21T23:00:00Z --to 2026-06-22T00:00:00Z --fps 1 --speed 3600 --width 16 --height 10"
                " --set /weather/grid/cells_x=32 --set /weather/grid/cells_y=32 --no-video --out " +
                dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto weather = [&](int i) { return nlohmann::json::parse(bytes(dir / frame(i, "json"))).at("weather"); };
  EXPECT_EQ(weather(0).at("start_utc"), "2026-06-20T23:28:04.800Z");
  EXPECT_EQ(weather(1).at("start_utc"), "2026-06-20T23:28:04.800Z");
  EXPECT_NEAR(weather(0).at("run_h").get<double>(), 23.5 + 115.2 / 3600.0, 1e-6);
  EXPECT_NEAR(weather(1).at("run_h").get<double>(), 24.5 + 115.2 / 3600.0, 1e-6);
}
}  // namespace
}  // namespace firmament
