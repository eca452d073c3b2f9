// The Beer shadow map (common/cloud_shadow.glsl) against the light march it replaces, on a simple
// layer: a stratus slab 1000-2000 m under a uniform weather map (coverage 1), looked at from below,
// sun 30 degrees from the zenith, sunlight only (no ambient, no aerial perspective), so the cloud's
// light differs between the two only through the optical depth towards the sun.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "common/cloud_shadow.glsl"
#include "common/cloud_weather.glsl"
#include "core/color.h"
#include "tests/clouds/cloud_test_support.h"

namespace firmament {
namespace {

class CloudShadow : public test::GpuTest {};

TEST(CloudShadowMath, OpticalDepthOfASlab) {
  // A slab from depth 100 m to 600 m of extinction 0.01 1/m: tau_max = 5.
  const glm::dvec4 bsm(100.0, 0.01, 5.0, 0.0);
  EXPECT_EQ(shared::cloudShadowOpticalDepth(bsm, 50.0), 0.0);
  EXPECT_NEAR(shared::cloudShadowOpticalDepth(bsm, 350.0), 2.5, 1e-12);
  EXPECT_EQ(shared::cloudShadowOpticalDepth(bsm, 5000.0), 5.0);
  const glm::dvec3 c =
      shared::cloudShadowCoordinate(glm::dvec3(10.0, 0.0, 5.0), glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0),
                                    glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0), 100.0, 20.0);
  EXPECT_NEAR(c.x, 0.6, 1e-12);
  EXPECT_NEAR(c.y, 0.5, 1e-12);
  EXPECT_NEAR(c.z, 15.0, 1e-12);
}

// Tolerance: the map spreads the optical depth evenly between the first and last cloud along the sun
// ray and has 40 km / 256 = 156 m texels; the light march samples 16 points in a cone over at most
// the layer's thickness. Over the cloud pixels the relative RMS difference of luminance must stay
// below 0.25 and the means within 15 %.
TEST_F(CloudShadow, AgreesWithTheLightMarchOnASlab) {
  const Scene s = test::cloudScene(
      {"/camera/pitch_deg=70", "/camera/fov_deg=60", "/camera/width=32", "/camera/height=18", "/sun/zenith_deg=30"},
      test::cloudSceneText(
          R"({"kind": "stratus", "bottom_m": 1000, "top_m": 2000, "coverage": 1, "extinction_scale": 0.2})"));
  SkyRenderOptions o = test::smallCloudOptions();
  o.cloudWeather = std::make_shared<CloudWeatherMap>(
      uniformCloudWeatherMap(glm::vec4(1.0f, 0.0f, 0.0f, float(shared::kCloudWeatherNoTop))));
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = AerialPerspective::Off;
  o.clouds.jitter = false;
  o.clouds.lightSteps = 16;
  o.clouds.viewSteps = 128;
  const RenderResult march = test::cloudRenderer().render(s, o);
  o.clouds.beerShadowMap = true;
  const RenderResult bsm = test::cloudRenderer().render(s, o);
  double sum2 = 0.0, ref2 = 0.0, meanMarch = 0.0, meanBsm = 0.0;
  int pixels = 0;
  for (size_t i = 0; i < march.clouds.pixelCount(); ++i) {
    if (march.clouds.pixels[4 * i + 3] > 0.95f) continue;
    const double a = luminanceRec709(march.clouds.pixels.data() + 4 * i),
                 b = luminanceRec709(bsm.clouds.pixels.data() + 4 * i);
    sum2 += (a - b) * (a - b);
    ref2 += a * a;
    meanMarch += a;
    meanBsm += b;
    ++pixels;
  }
  ASSERT_GT(pixels, 100);
  const double rel = std::sqrt(sum2 / ref2);
  std::printf(
      "Beer shadow map vs light march over %d cloud pixels: rel RMS %.3f, mean %.1f vs %.1f cd/m^2; light "
      "samples/pixel %.1f vs %.1f\n",
      pixels, rel, meanBsm / pixels, meanMarch / pixels, bsm.cloudSamples.lightPerPixel,
      march.cloudSamples.lightPerPixel);
  EXPECT_LT(rel, 0.25);
  EXPECT_NEAR(meanBsm / meanMarch, 1.0, 0.15);
  EXPECT_LT(bsm.cloudSamples.lightPerPixel, march.cloudSamples.lightPerPixel);
  // The map itself: finite and non-negative; where a sun ray meets cloud, its mean extinction is at
  // most the slab's majorant (stratus 0.05 x 0.2 = 0.01 1/m, density <= 1) and its front depth lies
  // before the end of the march. The slab covers the whole square, and so does the map: every texel's
  // march is its stretch inside the layer, wherever along the sun's azimuth it lies.
  // The march's length 2 L (clouds/cloud_block.cpp): L = (top - mid) / mu_s + 1 km + the 40 km square's
  // half diagonal x tan(theta_s), mid = 1500 m, top = 2000 m, theta_s = 30 deg.
  const double muS = std::cos(30.0 * shared::kPi / 180.0);
  const double marchLength =
      2.0 * (500.0 / muS + 1000.0 + 40000.0 / std::sqrt(2.0) * std::tan(30.0 * shared::kPi / 180.0));
  const std::vector<float> texels = test::cloudRenderer().cloudShadowMap();
  ASSERT_FALSE(texels.empty());
  int covered = 0;
  for (size_t i = 0; i + 3 < texels.size(); i += 4) {
    for (int k = 0; k < 4; ++k) ASSERT_TRUE(std::isfinite(texels[i + k]) && texels[i + k] >= 0.0f);
    if (texels[i + 2] <= 0.0f) continue;
    ++covered;
    ASSERT_LE(texels[i + 1], 0.01f * 1.0001f);
    ASSERT_LT(texels[i], marchLength);
  }
  std::printf("shadow map: %.1f %% of the texels see cloud\n", 100.0 * covered / double(texels.size() / 4));
  EXPECT_GT(covered, int(texels.size() / 4 / 20));
}

}  // namespace
}  // namespace firmament
