// Reduced-resolution clouds (docs/clouds.md "Resolution"): the march on a grid d times coarser,
// interpolated bilinearly to the image by clouds/upsample_clouds and composited there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/image_metrics.h"
#include "sky/render_plan.h"
#include "tests/clouds/cloud_test_support.h"

namespace firmament {
namespace {

class CloudResolution : public test::GpuTest {};

SkyRenderOptions withDivisor(int divisor) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.resolutionDivisor = divisor;
  return o;
}

TEST(CloudResolutionPlan, UpsampleListedOnlyWhenReduced) {
  EXPECT_FALSE(planRender(test::cloudScene()).has("clouds/upsample_clouds"));
  EXPECT_TRUE(planRender(test::cloudScene({"/clouds/resolution_divisor=2"})).has("clouds/upsample_clouds"));
  PlanOptions full;
  full.cloudResolutionDivisor = 1;
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/resolution_divisor=4"}), full).has("clouds/upsample_clouds"));
  EXPECT_FALSE(planRender(Scene::parse("{}", "<t>")).has("clouds/upsample_clouds"));
}

// The Beer shadow map is a scene knob too: planned (and baked) only when on.
TEST(CloudResolutionPlan, ShadowMapPlannedOnlyWhenOn) {
  EXPECT_FALSE(planRender(test::cloudScene()).has("clouds/bake_shadow_map"));
  EXPECT_TRUE(planRender(test::cloudScene({"/clouds/shadow_map=true"})).has("clouds/bake_shadow_map"));
  PlanOptions off;
  off.cloudShadowMap = false;
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/shadow_map=true"}), off).has("clouds/bake_shadow_map"));
}

TEST_F(CloudResolution, ShadowMapFromTheSceneRunsItsPass) {
  const RenderResult r =
      test::cloudRenderer().render(test::cloudScene({"/clouds/shadow_map=true"}), test::smallCloudOptions());
  bool baked = false;
  for (const auto& t : r.timings) baked = baked || t.label == "clouds/bake_shadow_map";
  EXPECT_TRUE(baked);
  for (const auto& t : r.timings) EXPECT_TRUE(r.plan.has(t.label)) << t.label;
}

// Where there is no cloud the upsampled transmittance is exactly 1 and the light 0: the sky is unchanged.
TEST_F(CloudResolution, NoCloudLeavesTheSkyUnchanged) {
  const Scene clear = test::cloudScene({"/clouds/layers/0/coverage=0"});
  const RenderResult full = test::cloudRenderer().render(clear, withDivisor(1));
  const RenderResult reduced = test::cloudRenderer().render(clear, withDivisor(2));
  ASSERT_EQ(full.image.pixels.size(), reduced.image.pixels.size());
  for (size_t i = 0; i < full.image.pixels.size(); ++i) ASSERT_EQ(full.image.pixels[i], reduced.image.pixels[i]) << i;
}

// The coarse march against the full one at a size where a cloud spans many pixels (the test's small,
// smooth noise: measured 0.30 % at d = 2 and 0.35 % at d = 4; the default cumulus scene at 640x360 with
// full noise measured 2.0 % and 3.2 %, docs/clouds.md). The mean is kept: bilinear interpolation of
// (L, T) neither adds nor removes light on average.
TEST_F(CloudResolution, ReducedAgreesWithFullResolution) {
  const Scene scene = test::cloudScene({"/camera/width=160", "/camera/height=90"});
  const RenderResult full = test::cloudRenderer().render(scene, withDivisor(1));
  double opacity = 0.0;
  for (size_t i = 0; i < full.clouds.pixelCount(); ++i) opacity += 1.0 - full.clouds.pixels[4 * i + 3];
  ASSERT_GT(opacity / double(full.clouds.pixelCount()), 0.2) << "the view must hold clouds";
  for (int divisor : {2, 4}) {
    const RenderResult reduced = test::cloudRenderer().render(scene, withDivisor(divisor));
    const ImageMetrics m = compareImages(reduced.image, full.image);
    std::printf("divisor %d: rel RMSE %.3f %%, rel bias %+.3f %%, view samples/pixel %.1f (full %.1f)\n", divisor,
                100.0 * m.luminance.relativeRmse, 100.0 * m.luminance.relativeMeanBias,
                reduced.cloudSamples.viewPerPixel, full.cloudSamples.viewPerPixel);
    EXPECT_LT(m.luminance.relativeRmse, divisor == 2 ? 0.02 : 0.03) << divisor;
    EXPECT_LT(std::abs(m.luminance.relativeMeanBias), 0.01) << divisor;
    // The march's samples fall with the pixel count (per image pixel: about 1/d^2).
    EXPECT_LT(reduced.cloudSamples.viewPerPixel, 1.5 * full.cloudSamples.viewPerPixel / double(divisor * divisor))
        << divisor;
    for (size_t i = 0; i < reduced.clouds.pixelCount(); ++i) {
      const float t = reduced.clouds.pixels[4 * i + 3];
      ASSERT_TRUE(t >= 0.0f && t <= 1.0f) << i;
    }
  }
}

// Image sizes that the divisor does not divide: the last coarse row and column cover the edge.
TEST_F(CloudResolution, SizesNotDivisibleAreFinite) {
  const Scene scene = test::cloudScene({"/camera/width=67", "/camera/height=37"});
  const RenderResult r = test::cloudRenderer().render(scene, withDivisor(4));
  for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
  for (float v : r.clouds.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
}

}  // namespace
}  // namespace firmament
