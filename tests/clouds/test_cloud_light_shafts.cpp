// Light shafts (docs/clouds.md "Light shafts"): the clouds' Beer shadow map shades the sun's single
// scattering in the aerial-perspective volume, and sky/cloud_light_shafts scales the sky behind by what
// that removes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/color.h"
#include "sky/render_plan.h"
#include "tests/clouds/cloud_test_support.h"

namespace firmament {
namespace {

class CloudLightShafts : public test::GpuTest {};

SkyRenderOptions shafts(bool on) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.beerShadowMap = true;
  o.clouds.lightShafts = on;
  return o;
}

// A view towards the sun, low, under a cumulus deck: the rays run kilometres through the air below it.
Scene shaftScene(const std::string& coverage) {
  return test::cloudScene({"/camera/width=96", "/camera/height=54", "/camera/pitch_deg=10", "/camera/yaw_deg=180",
                           "/clouds/layers/0/coverage=" + coverage});
}

TEST(CloudLightShaftsPlan, ListedOnlyWithTheShadowMapAndTheVolume) {
  EXPECT_FALSE(planRender(test::cloudScene()).has("sky/cloud_light_shafts"));  // the shadow map is off by default
  EXPECT_TRUE(planRender(test::cloudScene({"/clouds/shadow_map=true"})).has("sky/cloud_light_shafts"));
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/shadow_map=true", "/clouds/light_shafts=false"}))
                   .has("sky/cloud_light_shafts"));
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/shadow_map=true", "/clouds/aerial_perspective=march"}))
                   .has("sky/cloud_light_shafts"));
}

// No cloud, no shadow: with coverage 0 the shafts change nothing, bit for bit; the pass ran.
TEST_F(CloudLightShafts, NoCloudChangesNothing) {
  const Scene clear = shaftScene("0");
  const RenderResult with = test::cloudRenderer().render(clear, shafts(true));
  const RenderResult without = test::cloudRenderer().render(clear, shafts(false));
  bool ran = false;
  for (const auto& t : with.timings) ran = ran || t.label == "sky/cloud_light_shafts";
  EXPECT_TRUE(ran);
  ASSERT_EQ(with.image.pixels.size(), without.image.pixels.size());
  for (size_t i = 0; i < with.image.pixels.size(); ++i) ASSERT_EQ(with.image.pixels[i], without.image.pixels[i]) << i;
}

// Shadows only remove light: no pixel brighter (beyond float round-off), finite, and under the deck
// some clear-sky pixels are visibly darker.
TEST_F(CloudLightShafts, ShadowsOnlyRemoveLight) {
  const Scene deck = shaftScene("0.6");
  const RenderResult with = test::cloudRenderer().render(deck, shafts(true));
  const RenderResult without = test::cloudRenderer().render(deck, shafts(false));
  double darkest = 0.0, mean = 0.0;
  for (size_t i = 0; i < with.image.pixelCount(); ++i) {
    const double a = luminanceRec709(&with.image.pixels[4 * i]), b = luminanceRec709(&without.image.pixels[4 * i]);
    ASSERT_TRUE(std::isfinite(a) && a >= 0.0) << i;
    ASSERT_LE(a, b * (1.0 + 1e-5) + 1e-6) << i;
    darkest = std::max(darkest, b > 0.0 ? 1.0 - a / b : 0.0);
    mean += (b - a) / double(with.image.pixelCount());
  }
  std::printf("light shafts: darkest pixel -%.1f %%, mean -%.1f cd/m^2\n", 100.0 * darkest, mean);
  EXPECT_GT(darkest, 0.01);
  EXPECT_GT(mean, 0.0);
}

}  // namespace
}  // namespace firmament
