// The night scenes (scenes/night-full-moon.json, night-new-moon.json, twilight.json): their dates and
// places give the Moon's phase and the sun's altitude they are named for (the project's own ephemeris,
// astro/), and each renders, at a tiny size, as that night: finite, the night passes run, the light of the
// clouds the one that gives more ground illuminance, and the three in the order of their brightness.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "astro/moon_photometry.h"
#include "astro/sun.h"
#include "astro/time.h"
#include "core/color.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

struct Sky {
  double sunAltitudeDeg, moonAltitudeDeg, phaseAngleDeg, illuminatedFraction;
};

Sky skyOf(const Scene& scene) {
  const astro::AstroTime time = astro::makeAstroTime(scene.string("/time/utc"));
  const astro::GeodeticLocation place =
      astro::GeodeticLocation::fromDegrees(scene.number("/location/latitude_deg"),
                                           scene.number("/location/longitude_deg"), scene.number("/location/height_m"));
  const astro::MoonLight moon = astro::moonLight(time, place);
  return {astro::sunPosition(time, place).elevation() / kDegree, 90.0 - moon.zenith / kDegree,
          moon.phaseAngle / kDegree, moon.illuminatedFraction};
}

Scene load(const char* name) {
  return Scene::load(test::sourceDir() / "scenes" / name, {"/camera/width=32", "/camera/height=18"});
}

TEST(NightScenes, DatesAndPlacesGiveThePhaseAndTheSunTheyAreNamedFor) {
  const Sky full = skyOf(load("night-full-moon.json"));
  EXPECT_LT(full.phaseAngleDeg, 10.0);  // within a day or so of full (6.1 deg)
  EXPECT_GT(full.moonAltitudeDeg, 30.0);
  EXPECT_LT(full.sunAltitudeDeg, -18.0);  // astronomical night
  const Sky newMoon = skyOf(load("night-new-moon.json"));
  EXPECT_LT(newMoon.illuminatedFraction, 0.03);
  EXPECT_LT(newMoon.moonAltitudeDeg, 0.0);
  EXPECT_LT(newMoon.sunAltitudeDeg, -18.0);
  const Sky twilight = skyOf(load("twilight.json"));
  EXPECT_LT(twilight.sunAltitudeDeg, -3.0);  // civil to nautical twilight
  EXPECT_GT(twilight.sunAltitudeDeg, -9.0);
  EXPECT_GT(twilight.moonAltitudeDeg, 10.0);  // a crescent in the twilight
  EXPECT_GT(twilight.illuminatedFraction, 0.1);
  EXPECT_LT(twilight.illuminatedFraction, 0.5);
}

class NightScenesTest : public test::GpuTest {};

TEST_F(NightScenesTest, EachRendersAsItsNight) {
  SkyRenderer renderer(context());
  SkyRenderOptions options;
  options.cloudNoise.shapeSize = 32;
  options.cloudNoise.detailSize = 16;
  double mean[3];
  const char* names[3] = {"twilight.json", "night-full-moon.json", "night-new-moon.json"};
  for (int k = 0; k < 3; ++k) {
    const RenderResult r = renderer.render(load(names[k]), options);
    ASSERT_TRUE(r.night.run) << names[k];
    size_t bad = 0;
    mean[k] = 0.0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
      const float* p = r.image.pixels.data() + i * 4;
      for (int c = 0; c < 3; ++c) bad += !(std::isfinite(p[c]) && p[c] >= 0.0f);
      mean[k] += luminanceRec709(p) / double(r.image.pixelCount());
    }
    EXPECT_EQ(bad, 0u) << names[k];
    std::printf("%s: mean %.4g cd/m^2, light: %s\n", names[k], mean[k], r.light.reason.c_str());
    if (k == 0) {
      EXPECT_FALSE(r.light.moon);  // the twilight outshines the crescent: the Sun lights the clouds
    } else if (k == 1) {
      EXPECT_TRUE(r.light.moon);  // the full Moon lights the clouds
      EXPECT_TRUE(r.night.moonSky && r.night.moonDisc);
    } else {
      EXPECT_FALSE(r.night.moonSky);
    }
  }
  EXPECT_GT(mean[0], mean[1]);
  EXPECT_GT(mean[1], mean[2]);
}

}  // namespace
}  // namespace firmament
