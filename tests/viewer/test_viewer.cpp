// `firmament view --script` under Xvfb: a scripted flight at 160x90 (move, turn, climb, a time change),
// a screenshot, the view saved as a scene file; `firmament render` of that file must reproduce the
// screenshot (the screenshot is a still: every pixel marched). Validation on: zero messages (the viewer
// exits 3 on any). Also the script parser's errors and the fly camera's motion.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/exr_io.h"
#include "samples/viewer/fly_camera.h"
#include "samples/viewer/script.h"

namespace {

struct ShellRun {
  int exitCode = -1;
  std::string output;
};

ShellRun shell(const std::string& command) {
  ShellRun run;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

TEST(Viewer, ScriptedFlightScreenshotMatchesRenderOfSavedView) {
  // No skip: without Xvfb the test fails and says what to install.
  ASSERT_EQ(shell("command -v xvfb-run").exitCode, 0)
      << "xvfb-run not found: install the Debian package xvfb (scripts/run.sh installs it)";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "firmament-test-viewer";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string shot = (dir / "shot.exr").string(), view = (dir / "view.json").string();
  std::ofstream(dir / "flight.txt") << "speed 200\nkey W 1\ndrag 40 -10\nkey E 2\nadvance 0.5\nwait 2\n"
                                    << "screenshot " << shot << "\nsave " << view << "\nquit\n";
  const std::string exe = FIRMAMENT_EXE;
  const ShellRun viewerRun =
      shell("xvfb-run -a -s '-screen 0 320x240x24' " + exe +
            " view " FIRMAMENT_SOURCE_DIR "/scenes/cumulus.json --width 160 --height 90 --script " +
            (dir / "flight.txt").string());
  ASSERT_EQ(viewerRun.exitCode, 0) << viewerRun.output;
  EXPECT_EQ(viewerRun.output.find("validation"), std::string::npos) << viewerRun.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "shot.png"));
  ASSERT_TRUE(std::filesystem::exists(dir / "shot.view.json"));

  const ShellRun render = shell(exe + " render " + view + " -o " + (dir / "ref.exr").string());
  ASSERT_EQ(render.exitCode, 0) << render.output;
  const firmament::Image a = firmament::readExr(shot), b = firmament::readExr(dir / "ref.exr");
  ASSERT_EQ(a.width, 160);
  ASSERT_EQ(a.height, 90);
  ASSERT_EQ(b.width, a.width);
  ASSERT_EQ(b.height, a.height);
  // Tolerance: 1e-5 relative per channel (the same device and passes give the same floats; the margin
  // allows a driver's reordering). The flight must have moved the view: the time changed by 0.5 h.
  double worst = 0.0;
  for (size_t i = 0; i < a.pixelCount(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = a.pixels[i * a.channels + c], y = b.pixels[i * b.channels + c];
      ASSERT_TRUE(std::isfinite(x));
      worst = std::max(worst, std::abs(double(x) - y) / std::max(1e-3, std::abs(double(y))));
    }
  EXPECT_LE(worst, 1e-5);
  std::ifstream saved(view);
  const std::string text((std::istreambuf_iterator<char>(saved)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("2026-06-21"), std::string::npos) << "the saved view keeps the scene's date";
  std::filesystem::remove_all(dir);
}

TEST(Viewer, ScriptErrorsNameLineAndAllowedCommands) {
  try {
    firmament::viewer::parseScript("speed 10\nfly 3\n", "flight.txt");
    FAIL() << "no error";
  } catch (const firmament::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flight.txt:2: fly"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("allowed: key, drag"), std::string::npos) << e.what();
  }
  EXPECT_THROW(firmament::viewer::parseScript("key X 1\n", "s"), firmament::InputError);
  EXPECT_THROW(firmament::viewer::parseScript("screenshot a.png\n", "s"), firmament::InputError);
  EXPECT_EQ(firmament::viewer::parseScript("# c\n\nkey WE 0.5\nquit\n", "s").size(), 2u);
}

TEST(Viewer, FlyCameraMovesAlongTheYaw) {
  firmament::viewer::FlyState s;
  s.camera.yaw_deg = 90.0;  // east
  s.speed_m_s = 1000.0;
  firmament::viewer::fly(s, firmament::viewer::parseKeys("w"), 10.0);  // 10 km east at the equator
  EXPECT_NEAR(s.latitude_deg, 0.0, 1e-9);
  EXPECT_NEAR(s.longitude_deg, 10000.0 / (6371002.0) * 180.0 / M_PI, 1e-9);
  // The clouds' offset follows the flight, so they pass by (/clouds/offset_east_m).
  EXPECT_NEAR(s.cloudOffsetEast_m, 10000.0, 1e-9);
  EXPECT_NEAR(s.cloudOffsetNorth_m, 0.0, 1e-9);
  firmament::viewer::fly(s, firmament::viewer::parseKeys("e"), 1.0);
  EXPECT_NEAR(s.camera.heightAboveGround_m, 1002.0, 1e-9);
  firmament::viewer::drag(s, 50.0, 1000.0);  // 10 deg clockwise; pitch clamps at -90
  EXPECT_NEAR(s.camera.yaw_deg, 100.0, 1e-9);
  EXPECT_EQ(s.camera.pitch_deg, -90.0);
}

}  // namespace
