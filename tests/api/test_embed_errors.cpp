// Embedded mode's bad input (docs/api.md, "Embedded mode"): each mistake a host can make with the
// public API is an exception naming what was wrong and what is allowed, before anything is recorded.
// The working path is the example host's (CTests host_example*, samples/host_example/).
#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>

#include "firmament/embed.h"
#include "firmament/sky.h"

namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

const char* kClear = R"({"time": {"utc": "2026-06-21T09:00:00Z"}, "atmosphere": {"preset": "earth"}})";

TEST(EmbedErrors, MissingHostHandlesAreNamed) {
  const std::string m =
      messageOf([] { firmament::Sky::Builder().sceneJson(kClear).embedded(firmament::EmbeddedDevice{}).build(); });
  EXPECT_NE(m.find("VkInstance, VkPhysicalDevice, VkDevice and VkQueue"), std::string::npos) << m;
}

TEST(EmbedErrors, OfflineAndEmbeddedCallsDoNotMix) {
  auto sky = firmament::Sky::Builder().sceneJson(kClear).build();
  firmament::EmbeddedTargets targets;
  targets.width = 64;
  targets.height = 36;
  std::string m = messageOf([&] { sky->record(targets); });
  EXPECT_NE(m.find("Builder::embedded"), std::string::npos) << m;
  m = messageOf([&] { sky->lookups(); });
  EXPECT_NE(m.find("record() first"), std::string::npos) << m;
  EXPECT_TRUE(sky->validationMessages().empty());
}

TEST(EmbedErrors, TheCameraFrameIsTheSkyCamerasBasis) {
  // Yaw 90 (east), level: forward east, right south, up up; tan of half of 90 degrees is 1.
  const firmament::CameraFrame f = firmament::cameraFrame({2.0, 90.0, 0.0, 0.0, 90.0});
  EXPECT_NEAR(f.forward[0], 1.0, 1e-12);
  EXPECT_NEAR(f.forward[1], 0.0, 1e-12);
  EXPECT_NEAR(f.right[1], -1.0, 1e-12);
  EXPECT_NEAR(f.up[2], 1.0, 1e-12);
  EXPECT_NEAR(f.tanHalfFovX, 1.0, 1e-12);
}

}  // namespace
