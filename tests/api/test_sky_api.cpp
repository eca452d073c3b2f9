// The public API's quality knobs, plan and sequence frames (docs/api.md, "Reference"): what the
// command-line tool's render, timelapse and view are built on.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>

#include "firmament/sky.h"
#include "tests/support/test_paths.h"

namespace {

using firmament::Sky;

std::string inputErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const firmament::InputError& e) {
    return e.what();
  }
  return "";
}

const char* kClear = R"({"time": {"utc": "2026-06-21T09:00:00Z"}, "atmosphere": {"preset": "earth"},
                        "camera": {"width": 16, "height": 9}})";

bool hasPass(const firmament::SkyPlan& plan, const std::string& prefix) {
  return std::any_of(plan.passes.begin(), plan.passes.end(),
                     [&](const firmament::PlannedPassInfo& p) { return p.name.rfind(prefix, 0) == 0; });
}

TEST(SkyApi, QualityKnobsAreNamedByPathAndChecked) {
  const auto& knobs = firmament::qualityKnobs();
  ASSERT_FALSE(knobs.empty());
  for (const auto& k : knobs) {
    EXPECT_EQ(k.path.front(), '/') << k.path;
    EXPECT_FALSE(k.allowed.empty()) << k.path;
    EXPECT_FALSE(k.description.empty()) << k.path;
  }
  // An unknown knob names the known ones; a value out of range names the allowed ones.
  std::string m = inputErrorOf([] { Sky::Builder().sceneJson(kClear).quality("/atmosphere/steps=8").explain(); });
  EXPECT_NE(m.find("/atmosphere/view_steps"), std::string::npos) << m;
  m = inputErrorOf([] { Sky::Builder().sceneJson(kClear).quality("/atmosphere/view_steps=0").explain(); });
  EXPECT_NE(m.find("allowed: an integer from 1 to 4096"), std::string::npos) << m;
  m = inputErrorOf([] { Sky::Builder().sceneJson(kClear).quality("/atmosphere/spectral_samples=7").explain(); });
  EXPECT_NE(m.find("a multiple of 3"), std::string::npos) << m;
  m = inputErrorOf([] { Sky::Builder().sceneJson(kClear).quality("/atmosphere/sky=fast").explain(); });
  EXPECT_NE(m.find("lut, march"), std::string::npos) << m;
}

// Every row of the cloud march's knob table (clouds/cloud_knobs.h) is a quality knob /clouds/march/ID,
// with the table's range; the plan follows it, and a bad value or name is refused naming what is allowed.
TEST(SkyApi, CloudMarchKnobsAreQualityKnobsByTheirIdentifiers) {
  const auto& knobs = firmament::qualityKnobs();
  const auto lightSteps = std::find_if(knobs.begin(), knobs.end(), [](const firmament::QualityKnob& k) {
    return k.path == "/clouds/march/light_steps";
  });
  ASSERT_NE(lightSteps, knobs.end());
  EXPECT_EQ(lightSteps->allowed, "integer in [1, 256]");
  EXPECT_EQ(lightSteps->defaultValue, "null");
  const std::string cumulus = (firmament::test::sourceDir() / "scenes" / "cumulus.json").string();
  EXPECT_TRUE(hasPass(Sky::Builder().sceneFile(cumulus).explain(), "clouds/bake_deep_shadow"));
  EXPECT_FALSE(hasPass(Sky::Builder().sceneFile(cumulus).quality("/clouds/march/deep_shadow_map=false").explain(),
                       "clouds/bake_deep_shadow"));
  std::string m =
      inputErrorOf([&] { Sky::Builder().sceneFile(cumulus).quality("/clouds/march/light_steps=0").explain(); });
  EXPECT_NE(m.find("quality /clouds/march/light_steps=0"), std::string::npos) << m;
  EXPECT_NE(m.find("[1, 256]"), std::string::npos) << m;
  m = inputErrorOf([&] { Sky::Builder().sceneFile(cumulus).quality("/clouds/march/steps=3").explain(); });
  EXPECT_NE(m.find("no such cloud knob"), std::string::npos) << m;
  EXPECT_NE(m.find("light_steps"), std::string::npos) << m;
}

TEST(SkyApi, ThePlanFollowsTheSceneAndTheKnobs) {
  // No clouds section: no cloud pass runs, and the plan says why they are left out.
  const firmament::SkyPlan clear = Sky::Builder().sceneJson(kClear).explain();
  EXPECT_EQ(clear.width, 16);
  EXPECT_EQ(clear.height, 9);
  EXPECT_TRUE(hasPass(clear, "atmosphere/transmittance_lut"));
  EXPECT_FALSE(hasPass(clear, "clouds/"));
  EXPECT_TRUE(std::any_of(clear.omitted.begin(), clear.omitted.end(),
                          [](const firmament::LeftOutPass& p) { return p.name.rfind("clouds", 0) == 0; }));
  EXPECT_NE(clear.text.find("atmosphere/transmittance_lut"), std::string::npos);
  // A cloud scene plans the march.
  const std::string cumulus = (firmament::test::sourceDir() / "scenes" / "cumulus.json").string();
  EXPECT_TRUE(hasPass(Sky::Builder().sceneFile(cumulus).explain(), "clouds/render_clouds"));
  // The sky marched per pixel instead of the sky-view table.
  const firmament::SkyPlan march = Sky::Builder().sceneJson(kClear).quality("/atmosphere/sky=march").explain();
  EXPECT_TRUE(hasPass(clear, "sky/sky_view_lut"));
  EXPECT_FALSE(hasPass(march, "sky/sky_view_lut"));
}

TEST(SkyApi, SequenceFramesMoveTheClockFromTheBuiltScene) {
  auto sky = Sky::Builder().sceneJson(kClear).build();
  EXPECT_EQ(sky->quality("/atmosphere/view_steps"), "32");
  sky->setQuality("/atmosphere/view_steps=48");
  EXPECT_EQ(sky->quality("/atmosphere/view_steps"), "48");
  EXPECT_FALSE(inputErrorOf([&] { sky->setQuality("/atmosphere/view_steps=-1"); }).empty());
  EXPECT_EQ(sky->quality("/atmosphere/view_steps"), "48");  // a refused knob leaves it
  // A cloud march knob: null (the scene's quality preset decides) until set.
  EXPECT_EQ(sky->quality("/clouds/march/light_steps"), "null");
  sky->setQuality("/clouds/march/light_steps=12");
  EXPECT_EQ(sky->quality("/clouds/march/light_steps"), "12");
  sky->setQuality("/clouds/march/aerial_perspective=march");
  EXPECT_EQ(sky->quality("/clouds/march/aerial_perspective"), "\"march\"");

  const std::string built = sky->get("/time/utc");
  sky->checkSequenceFrame(7200.0);
  EXPECT_EQ(sky->get("/time/utc"), built);  // a check changes nothing
  firmament::SkyCamera camera = sky->camera();
  camera.yaw_deg = 123.5;
  sky->set("/camera/fov_deg=40");
  sky->setSequenceFrame(7200.0, camera);
  EXPECT_EQ(sky->get("/time/utc"), "\"2026-06-21T11:00:00.000Z\"");  // no sun section: the sun's clock moves
  EXPECT_EQ(sky->camera().yaw_deg, 123.5);
  EXPECT_EQ(sky->camera().fov_deg, camera.fov_deg);  // fields set since build() are the frame's
  sky->setSequenceFrame(0.0);
  EXPECT_EQ(sky->camera().yaw_deg, Sky::Builder().sceneJson(kClear).build()->camera().yaw_deg);
  EXPECT_EQ(firmament::utcSecondsBetween("2026-06-21T09:00:00Z", "2026-06-22T09:30:00Z"), 86400.0 + 1800.0);
  EXPECT_EQ(firmament::utcPlusSeconds("2026-12-31T23:00:00Z", 7200.0), "2027-01-01T01:00:00.000Z");
}

}  // namespace
