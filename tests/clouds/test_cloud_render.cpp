// The cloud pass inside the sky renderer: what runs, what a zero cloud changes (nothing), robustness
// over camera and sun positions, and convergence in the number of view steps.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "clouds/cloud_pass.h"
#include "core/color.h"
#include "core/error.h"
#include "core/image_metrics.h"
#include "sky/render_plan.h"
#include "tests/clouds/cloud_test_support.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

class CloudRender : public test::GpuTest {};

double maxAbsDifference(const Image& a, const Image& b) {
  double m = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) m = std::max(m, double(std::abs(a.pixels[i] - b.pixels[i])));
  return m;
}

// The robustness sweeps render 16x9 images, whose time goes almost all to the per-frame maps' bakes at
// their default 256 texels (~0.5 s a render on lavapipe); at 64 texels the same shaders run in about a
// sixteenth of it.
void useSmallMaps(SkyRenderOptions& o) {
  o.clouds.deepShadowMapSize = 64;
  o.clouds.columnMapSize = 64;
  o.clouds.otherLayerMapSize = 64;
}

void expectFiniteNonNegative(const Image& image, const std::string& what) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    ASSERT_TRUE(std::isfinite(image.pixels[i])) << what << " at " << i;
    ASSERT_GE(image.pixels[i], 0.0f) << what << " at " << i;
  }
}

TEST(CloudPlan, CloudsListedOnlyWithLayers) {
  RenderPlan clear = planRender(Scene::parse("{}", "<t>"));
  EXPECT_FALSE(clear.has("clouds/render_clouds"));
  RenderPlan cloudy = planRender(test::cloudScene());
  EXPECT_TRUE(cloudy.has("clouds/render_clouds"));
  EXPECT_TRUE(cloudy.has("clouds/bake_noise_3d"));
}

TEST_F(CloudRender, ZeroDensityOrCoverageLeavesTheSkyUnchanged) {
  SkyRenderOptions o = test::smallCloudOptions();
  Scene clearScene =
      test::cloudScene({}, R"({"location": {"height_m": 500}, "sun": {"zenith_deg": 40, "azimuth_deg": 180},
    "camera": {"height_above_ground_m": 2, "yaw_deg": 0, "pitch_deg": 50, "fov_deg": 80, "width": 64, "height": 36}})");
  RenderResult clear = test::cloudRenderer().render(clearScene, o);
  for (const char* zero :
       {"/clouds/layers/0/coverage=0", "/clouds/layers/0/extinction_scale=0", "/clouds/layers/0/density=0"}) {
    RenderResult r = test::cloudRenderer().render(test::cloudScene({zero}), o);
    EXPECT_EQ(maxAbsDifference(r.image, clear.image), 0.0) << zero;
    for (size_t i = 0; i < r.clouds.pixelCount(); ++i) ASSERT_EQ(r.clouds.pixels[4 * i + 3], 1.0f) << zero;
  }
  // And with cloud, something changes.
  RenderResult cloudy = test::cloudRenderer().render(test::cloudScene(), o);
  EXPECT_GT(maxAbsDifference(cloudy.image, clear.image), 0.0);
}

TEST_F(CloudRender, CoverageOneIsNearlyOpaqueOverhead) {
  SkyRenderOptions o = test::smallCloudOptions();
  RenderResult r = test::cloudRenderer().render(
      test::cloudScene({"/clouds/layers/0/coverage=1", "/camera/pitch_deg=90", "/camera/fov_deg=30"}), o);
  expectFiniteNonNegative(r.image, "image");
  double meanT = 0.0;
  for (size_t i = 0; i < r.clouds.pixelCount(); ++i) meanT += r.clouds.pixels[4 * i + 3];
  meanT /= double(r.clouds.pixelCount());
  std::printf("coverage 1, looking up: mean cloud transmittance %.4f\n", meanT);
  EXPECT_LT(meanT, 0.2);
}

// Camera below, at the bottom boundary, inside, at the top boundary and above the shell; sun at the
// zenith, the horizon and below it; views up, level (tangent to the shells from their boundaries)
// and down; the air in front of the clouds from the aerial-perspective volume (default) and from the
// per-pixel march.
TEST_F(CloudRender, FiniteAndNonNegativeEverywhere) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 24;
  o.clouds.lightSteps = 3;
  useSmallMaps(o);
  const double ground = 500.0;
  for (AerialPerspective air : {AerialPerspective::Volume, AerialPerspective::March})
    for (double height : {2.0, 1500.0, 2700.0, 4000.0, 6000.0}) {
      o.clouds.aerialPerspective = air;
      for (double sunZenith : {0.0, 90.0, 96.0}) {
        for (double pitch : {60.0, 0.0, -30.0}) {
          Scene s = test::cloudScene({"/camera/height_above_ground_m=" + std::to_string(height),
                                      "/sun/zenith_deg=" + std::to_string(sunZenith),
                                      "/camera/pitch_deg=" + std::to_string(pitch), "/camera/width=16",
                                      "/camera/height=9", "/location/height_m=" + std::to_string(ground)});
          RenderResult r = test::cloudRenderer().render(s, o);
          const std::string what = std::string(aerialPerspectiveName(air)) + " height " + std::to_string(height) +
                                   " sun " + std::to_string(sunZenith) + " pitch " + std::to_string(pitch);
          expectFiniteNonNegative(r.image, what);
          expectFiniteNonNegative(r.clouds, what + " (clouds)");
          for (size_t i = 0; i < r.clouds.pixelCount(); ++i) ASSERT_LE(r.clouds.pixels[4 * i + 3], 1.0f) << what;
        }
      }
    }
}

// The higher orders' build-up along the view (CloudMarchSettings::msBuildUpScale; the closed form is
// checked in test_cloud_build_up.cpp): on the GPU it only takes light off, pixel by pixel (the same
// jitter, so the same samples; 1e-5 relative for float rounding), leaves a pixel whose march stopped at
// its early exit (alpha 0: the rest of the ray opaque) exactly as it was, and darkens the thin pixels
// (0.1 < T < 0.95), where the cloud behind each sample is thin (extinction x 0.1, views up 50 and 10 deg).
TEST_F(CloudRender, BuildUpAlongTheViewOnlyDarkensWhereTheCloudBehindIsThin) {
  SkyRenderOptions o = test::smallCloudOptions();
  int opaqueSeen = 0;
  for (const char* pitch : {"/camera/pitch_deg=50", "/camera/pitch_deg=10"}) {
    const Scene scene = test::cloudScene({pitch, "/clouds/layers/0/extinction_scale=0.1"});
    o.clouds.msBuildUpScale = 4.0;
    const RenderResult with = test::cloudRenderer().render(scene, o);
    o.clouds.msBuildUpScale = 0.0;
    const RenderResult without = test::cloudRenderer().render(scene, o);
    double thinWith = 0.0, thinWithout = 0.0;
    int opaque = 0, thin = 0;
    for (size_t i = 0; i < with.clouds.pixelCount(); ++i) {
      const float* a = &with.clouds.pixels[4 * i];
      const float* b = &without.clouds.pixels[4 * i];
      ASSERT_EQ(a[3], b[3]) << pitch << " pixel " << i;  // the transmittance is not the light's
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(a[c]) && a[c] >= 0.0f) << pitch << " pixel " << i;
        ASSERT_LE(a[c], b[c] * (1.0f + 1e-5f) + 1e-6f) << pitch << " pixel " << i;
      }
      if (a[3] == 0.0f) {
        ++opaque;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(a[c], b[c]) << pitch << " pixel " << i;
      }
      if (a[3] > 0.1f && a[3] < 0.95f) {
        ++thin;
        thinWith += luminanceRec709(a);
        thinWithout += luminanceRec709(b);
      }
    }
    std::printf("%s: %d opaque pixels unchanged; %d thin pixels, luminance with the build-up / without %.3f\n", pitch,
                opaque, thin, thinWith / thinWithout);
    EXPECT_GT(thin, 20) << pitch;
    EXPECT_LT(thinWith, 0.99 * thinWithout) << pitch;  // measured 0.974 (up 50 deg) and 0.978 (up 10 deg)
    opaqueSeen += opaque;
  }
  EXPECT_GT(opaqueSeen, 100);  // measured 316, all in the view up 10 deg
}

// The octaves' low-sun scale (cloudOctaveLowSunScale; each layer's mu_0, here overridden for all by
// CloudMarchSettings::octaveLowSunMu): sun 80 deg from the zenith (mu_s 0.174). With mu_0 below mu_s nothing changes
// (bit for bit); with mu_0 0.34 the higher orders' light scales by 0.51, so every pixel gets no brighter and the image
// darker; one octave (single scattering) is not touched. The transmittance never changes.
TEST_F(CloudRender, OctaveLowSunScaleOnlyDimsTheHigherOrdersBelowItsSun) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.ambient = false;
  for (const char* octaves : {"/clouds/lighting/ms_octaves=3", "/clouds/lighting/ms_octaves=1"}) {
    const Scene scene = test::cloudScene({"/sun/zenith_deg=80", octaves});
    o.clouds.octaveLowSunMu = 0.0;
    const RenderResult off = test::cloudRenderer().render(scene, o);
    o.clouds.octaveLowSunMu = 0.1;
    const RenderResult above = test::cloudRenderer().render(scene, o);
    o.clouds.octaveLowSunMu = 0.34;
    const RenderResult scaled = test::cloudRenderer().render(scene, o);
    double sumOff = 0.0, sumScaled = 0.0;
    for (size_t i = 0; i < off.clouds.pixelCount(); ++i) {
      const float* a = &off.clouds.pixels[4 * i];
      const float* b = &above.clouds.pixels[4 * i];
      const float* c = &scaled.clouds.pixels[4 * i];
      ASSERT_EQ(a[3], c[3]) << octaves << " pixel " << i;
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(a[k], b[k]) << octaves << " pixel " << i;
        ASSERT_TRUE(std::isfinite(c[k]) && c[k] >= 0.0f) << octaves << " pixel " << i;
        ASSERT_LE(c[k], a[k] * (1.0f + 1e-5f) + 1e-6f) << octaves << " pixel " << i;
      }
      sumOff += luminanceRec709(a);
      sumScaled += luminanceRec709(c);
    }
    std::printf("%s: luminance with mu_0 0.34 / off %.3f\n", octaves, sumScaled / sumOff);
    if (std::string(octaves).back() == '1')
      EXPECT_NEAR(sumScaled, sumOff, 1e-5 * sumOff);  // single scattering alone: unchanged
    else
      EXPECT_LT(sumScaled, 0.9 * sumOff);  // measured 0.821
  }
}

// Two layers (cumulus under cirrus): the camera under, in, between and above them, the sun overhead,
// grazing and below the horizon, rays up, level and down. Finite, non-negative, T <= 1 with all
// octaves; and with one octave (single scattering) the light through the other layer only takes light
// away: per pixel, no brighter than each layer lit through its own layer only (the same jitter, so the
// same samples; 1e-5 relative for float rounding). With more octaves it may add light, as it should:
// their scattered-only attenuation e^(-a^i tau) - e^(-tau) grows with tau while tau is small (light the
// other layer scattered towards the sample; a side view under a high sun measured +13 % at one pixel).
// Each layer takes its own type's low-sun mu_0 into the march (CloudLayerSettings::msLowSunMu): under a
// sun 80 deg from the zenith a cumulus layer renders bit for bit as with its mu_0 (0.358) for every layer, a
// stratocumulus layer as with the scale off, and the two together as neither (the check can fail: one
// shared value would match one of them).
TEST_F(CloudRender, LayerTypesTakeTheirOwnLowSunScale) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.ambient = false;
  const std::string cumulus = R"({"kind": "cumulus", "bottom_m": 2500, "top_m": 4000, "coverage": 0.6})";
  const std::string stratocumulus = R"({"kind": "stratocumulus", "bottom_m": 800, "top_m": 1600, "coverage": 0.6})";
  auto render = [&](const std::string& layers, double mu0) {
    const Scene scene = test::cloudScene({"/sun/zenith_deg=80", "/camera/pitch_deg=20"}, test::cloudSceneText(layers));
    o.clouds.octaveLowSunMu = mu0;
    return test::cloudRenderer().render(scene, o).clouds.pixels;
  };
  const double cumulusMu0 = cloudTypeMultipleScattering(shared::kCloudCumulus).lowSunMu;
  ASSERT_GT(cumulusMu0, 0.174);
  ASSERT_EQ(cloudTypeMultipleScattering(shared::kCloudStratocumulus).lowSunMu, 0.0);
  EXPECT_EQ(render(cumulus, -1.0), render(cumulus, cumulusMu0));
  EXPECT_NE(render(cumulus, -1.0), render(cumulus, 0.0));
  EXPECT_EQ(render(stratocumulus, -1.0), render(stratocumulus, 0.0));
  const std::string both = stratocumulus + ", " + cumulus;
  const auto own = render(both, -1.0);
  EXPECT_NE(own, render(both, 0.0));
  EXPECT_NE(own, render(both, cumulusMu0));
}

// The reflected light's depth scale a_r / s under the low-sun scale (CloudMarchSettings::reflectedLowSunDepth,
// cloudReflectedLowSunDepthScale): a cumulus layer under a sun 40 deg from the zenith (above mu_0) renders bit
// for bit with it off; under a sun 80 deg from the zenith it takes light away (no pixel brighter, the image
// darker: the check can fail).
TEST_F(CloudRender, ReflectedLowSunDepthOnlyUnderALowSun) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.ambient = false;
  const std::string cumulus = R"({"kind": "cumulus", "bottom_m": 2500, "top_m": 4000, "coverage": 0.6})";
  auto render = [&](double zenith, bool depth) {
    const Scene scene = test::cloudScene({"/sun/zenith_deg=" + std::to_string(zenith), "/camera/pitch_deg=20"},
                                         test::cloudSceneText(cumulus));
    o.clouds.reflectedLowSunDepth = depth;
    return test::cloudRenderer().render(scene, o).clouds.pixels;
  };
  EXPECT_EQ(render(40.0, true), render(40.0, false));
  const auto on = render(80.0, true), off = render(80.0, false);
  ASSERT_EQ(on.size(), off.size());
  double sumOn = 0.0, sumOff = 0.0;
  for (size_t i = 0; i < on.size(); i += 4)
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(on[i + c], off[i + c] * (1.0f + 1e-5f) + 1e-6f);
      sumOn += on[i + c], sumOff += off[i + c];
    }
  std::printf("sun 80 deg: the image's light with a_r / s %.4f of that with a_r\n", sumOn / sumOff);
  EXPECT_LT(sumOn, 0.99 * sumOff);
}

TEST_F(CloudRender, TwoLayersFiniteAndTheOtherLayerOnlyShadows) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 24;
  o.clouds.lightSteps = 3;
  useSmallMaps(o);
  const std::string layers = test::cloudSceneText(
      R"({"kind": "cumulus", "bottom_m": 1500, "top_m": 3000, "coverage": 0.7}, {"kind": "cirrus", "bottom_m": 7000, "top_m": 9000, "coverage": 0.8, "extinction_scale": 10})");
  int darker = 0;
  for (int octaves : {3, 1})
    for (double height : {2.0, 2000.0, 5000.0, 8000.0, 12000.0})
      for (double sunZenith : {0.0, 89.0, 96.0})
        for (double pitch : {60.0, 0.0, -30.0}) {
          Scene s = test::cloudScene(
              {"/camera/height_above_ground_m=" + std::to_string(height),
               "/sun/zenith_deg=" + std::to_string(sunZenith), "/camera/pitch_deg=" + std::to_string(pitch),
               "/camera/width=16", "/camera/height=9", "/clouds/lighting/ms_octaves=" + std::to_string(octaves)},
              layers);
          o.clouds.lightThroughOtherLayers = true;
          const RenderResult both = test::cloudRenderer().render(s, o);
          o.clouds.lightThroughOtherLayers = false;
          const RenderResult own = test::cloudRenderer().render(s, o);
          const std::string what = std::to_string(octaves) + " octaves, height " + std::to_string(height) + " sun " +
                                   std::to_string(sunZenith) + " pitch " + std::to_string(pitch);
          expectFiniteNonNegative(both.image, what);
          expectFiniteNonNegative(both.clouds, what + " (clouds)");
          for (size_t i = 0; i < both.clouds.pixelCount(); ++i) {
            ASSERT_LE(both.clouds.pixels[4 * i + 3], 1.0f) << what;
            ASSERT_EQ(both.clouds.pixels[4 * i + 3], own.clouds.pixels[4 * i + 3]) << what;  // the view ray is the same
            if (octaves > 1) continue;
            for (int c = 0; c < 3; ++c) {
              const float withOther = both.clouds.pixels[4 * i + c], ownOnly = own.clouds.pixels[4 * i + c];
              ASSERT_LE(withOther, ownOnly * (1.0f + 1e-5f) + 1e-6f) << what << " pixel " << i;
              darker += withOther < 0.99f * ownOnly;
            }
          }
        }
  EXPECT_GT(darker, 0);  // the other layer does shadow somewhere (the check can fail)
}

// The march compiled for the options a frame uses (cloudMarchFeatures, a specialization constant)
// gives the same image, bit for bit, as the general one with every option compiled in: single layer,
// two layers (light through the other one), the Beer shadow map, the light cone, a weather simulation's map (the
// coverage reach), the octaves without the reflected light, and a sun 1 degree above the horizon, where the reflected
// light's way behind comes from the deep shadow map alone (its march left out: the general march would show any sample
// that needed it).
TEST_F(CloudRender, SpecializedMarchMatchesTheGeneralOne) {
  SkyRenderOptions base = test::smallCloudOptions();
  base.clouds.viewSteps = 32;
  base.clouds.lightSteps = 4;
  const std::string twoLayers = test::cloudSceneText(
      R"({"kind": "cumulus", "bottom_m": 1500, "top_m": 3000, "coverage": 0.7}, {"kind": "stratocumulus", "bottom_m": 4000, "top_m": 4800, "coverage": 0.6})");
  struct Case {
    std::string name;
    Scene scene;
    SkyRenderOptions options;
    uint32_t features;
    double sunZenith_deg = 40.0;  // the scene's (test::cloudSceneText)
  };
  std::vector<Case> cases;
  const Scene single = test::cloudScene({"/camera/width=32", "/camera/height=18"});
  cases.push_back({"single layer", single, base, 3328u});
  // The octaves alone (no reflected light: feature 2048 off).
  cases.push_back(
      {"no reflected light",
       test::cloudScene({"/camera/width=32", "/camera/height=18", "/clouds/lighting/reflected_light=false"}), base,
       1280u});
  const Scene two = test::cloudScene({"/camera/width=32", "/camera/height=18"}, twoLayers);
  cases.push_back({"two layers", two, base, 3425u});
  SkyRenderOptions marched = base;
  marched.clouds.otherLayerMap = false;
  cases.push_back({"two layers, crossings marched", two, marched, 3489u});
  SkyRenderOptions columnsMarched = base;
  columnsMarched.clouds.columnMap = false;
  cases.push_back({"vertical marches", single, columnsMarched, 3584u});
  SkyRenderOptions everyLightStep = base;
  everyLightStep.clouds.deepShadowMap = false;
  cases.push_back({"every light step marched", single, everyLightStep, 6400u});  // the way behind marched too
  cases.push_back({"two layers, every light step marched", two, everyLightStep, 6497u});
  SkyRenderOptions shadow = base;
  shadow.clouds.beerShadowMap = true;
  cases.push_back({"shadow map", single, shadow, 7426u});  // the way behind marched on the shadow map
  // The sun low: 1 degree above the horizon every sample's sun ray still climbs (the way behind from the
  // deep shadow map alone, bit 4096 left out); 0.5 degrees below it, some descend (bit 4096 in).
  cases.push_back(
      {"sun 1 deg above the horizon",
       test::cloudScene({"/camera/width=32", "/camera/height=18", "/sun/zenith_deg=89", "/camera/pitch_deg=3"}), base,
       3328u, 89.0});
  cases.push_back(
      {"sun 0.5 deg below the horizon",
       test::cloudScene({"/camera/width=32", "/camera/height=18", "/sun/zenith_deg=90.5", "/camera/pitch_deg=3"}), base,
       7424u, 90.5});
  SkyRenderOptions cone = base;
  cone.clouds.lightCone = 0.15;
  cases.push_back({"light cone", single, cone, 3344u});
  cases.push_back(
      {"weather map",
       Scene::load(test::sourceDir() / "scenes" / "thunderstorm.json",
                   {"/weather/grid/cells_x=64", "/weather/grid/cells_y=64", "/camera/width=40", "/camera/height=23"}),
       base, 3332u});
  for (Case& c : cases) {
    CloudSettings settings = CloudSettings::fromScene(c.scene);
    c.options.clouds.apply(settings.march);
    CloudView view;
    view.cameraPosition = glm::dvec3(0.0, 0.0, 6360e3 + 500.0 + 2.0);
    const double zenith = glm::radians(c.sunZenith_deg);
    view.sunDirection = glm::dvec3(std::sin(zenith), 0.0, std::cos(zenith));
    EXPECT_EQ(cloudMarchFeatures(settings, c.features == 3332u, sunClearsEveryCloudSample(settings.march, view)),
              c.features)
        << c.name;
    c.options.clouds.specializeMarch = true;
    const RenderResult specialized = test::cloudRenderer().render(c.scene, c.options);
    c.options.clouds.specializeMarch = false;
    const RenderResult general = test::cloudRenderer().render(c.scene, c.options);
    size_t cloudy = 0;
    for (size_t i = 0; i < general.clouds.pixelCount(); ++i) cloudy += general.clouds.pixels[4 * i + 3] < 0.95f;
    EXPECT_GT(cloudy, general.clouds.pixelCount() / 10) << c.name;  // there is cloud to compare
    ASSERT_EQ(specialized.clouds.pixels, general.clouds.pixels) << c.name;
    ASSERT_EQ(specialized.image.pixels, general.image.pixels) << c.name;
  }
}

// Relative RMS luminance difference of two cloud layers.
double relativeRmsLuminance(const Image& img, const Image& truth) {
  double sum2 = 0.0, ref2 = 0.0;
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    const double y = luminanceRec709(img.pixels.data() + 4 * i), t = luminanceRec709(truth.pixels.data() + 4 * i);
    sum2 += (y - t) * (y - t);
    ref2 += t * t;
  }
  return std::sqrt(sum2 / std::max(ref2, 1e-30));
}

// The per-frame maps' test views (64x36): the sun high and low, looking up and towards the horizon.
// Without the reflected light: these tests measure the maps' optical depths against the marched
// ones, and the reflected light's way behind a sample has estimators of its own (the deep map's whole
// crossing less the way to the sun, or lightSteps / 2 marched samples with the deep map off) whose
// difference would add to what they measure (at sun 80 deg, two layers: 5.5-6.9 % instead of 2.6-3.5 %).
std::vector<std::pair<std::string, Scene>> mapTestViews(const std::string& layers) {
  std::vector<std::pair<std::string, Scene>> views;
  for (double sunZenith : {35.0, 80.0})
    for (double pitch : {30.0, 5.0})
      views.emplace_back("sun " + std::to_string(sunZenith) + " pitch " + std::to_string(pitch),
                         test::cloudScene({"/sun/zenith_deg=" + std::to_string(sunZenith),
                                           "/camera/pitch_deg=" + std::to_string(pitch), "/camera/width=64",
                                           "/camera/height=36", "/clouds/lighting/reflected_light=false"},
                                          layers));
  return views;
}

// The map tests' two layers: cumulus under a stratocumulus deck.
std::string mapTestTwoLayers() {
  return test::cloudSceneText(
      R"({"kind": "cumulus", "bottom_m": 1500, "top_m": 2700, "coverage": 0.6}, {"kind": "stratocumulus", "bottom_m": 4000, "top_m": 4800, "coverage": 0.6})");
}

// The column map (clouds/column_map.glsl) against marching up and down from each lit sample: cumulus,
// the sun high and low, looking up and towards the horizon, 64x36. Both converge to the same vertical
// optical depths: the fine map (1024 texels, 64 levels) and the fine march (64 light steps: 32 up; the
// floor's way down keeps its 2 samples) differ by 0.4-3.1 % relative RMS over the image's luminance
// (measured; the most where the floor's 2 samples matter, the sun high), and the default map (256
// texels, 8 levels) is 0.6-4.1 % from the fine one, as the default march (6 light steps: 3 up) was
// 1.4-4.1 % from its own fine version (a scratch run).
TEST_F(CloudRender, ColumnMapMatchesTheVerticalMarches) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 32;
  o.clouds.deepShadowMap = false;  // the sun's light march whole, as when the numbers above were measured
  for (const auto& [what, s] : mapTestViews(test::cloudSceneText())) {
    o.clouds.lightSteps = 64;
    o.clouds.columnMap = false;
    const RenderResult marchedFine = test::cloudRenderer().render(s, o);
    o.clouds.columnMap = true;
    o.clouds.columnMapSize = 1024;
    o.clouds.columnMapLevels = 64;
    const RenderResult mapFine = test::cloudRenderer().render(s, o);
    o.clouds.lightSteps = 6;
    o.clouds.columnMapSize = 256;
    o.clouds.columnMapLevels = 8;
    const RenderResult map = test::cloudRenderer().render(s, o);
    expectFiniteNonNegative(map.image, what);
    const double fine = relativeRmsLuminance(mapFine.image, marchedFine.image);
    const double coarse = relativeRmsLuminance(map.image, mapFine.image);
    std::printf("%s: fine map against fine march %.4f; the default map against the fine map %.4f\n", what.c_str(), fine,
                coarse);
    EXPECT_LT(fine, 0.05) << what;
    EXPECT_LT(coarse, 0.06) << what;
    EXPECT_GT(map.cloudSamples.mapPerPixel, 0.0) << what;
  }
}

// The other layers' light from their map (clouds/other_layer_map.glsl) against marching each lit
// sample's crossings: cumulus under stratocumulus, the sun high and low, looking up and towards the
// horizon. The map loses only the detail finer than its texels: its error falls as it grows (measured
// relative RMS over the image's luminance, 64x36: 8-16 % at 64 texels, 1.7-3.5 % at the default 256,
// 0.4-0.5 % at 1024), under 5 % at the default, and the shadow is there (the check can fail).
TEST_F(CloudRender, OtherLayerMapMatchesTheMarchedCrossings) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 32;
  o.clouds.lightSteps = 6;
  o.clouds.deepShadowMap = false;  // the own layer's light march whole, as when the numbers above were measured
  const std::string layers = mapTestTwoLayers();
  for (const auto& [what, s] : mapTestViews(layers)) {
    o.clouds.otherLayerMap = false;
    const RenderResult marched = test::cloudRenderer().render(s, o);
    o.clouds.lightThroughOtherLayers = false;
    const RenderResult own = test::cloudRenderer().render(s, o);
    o.clouds.lightThroughOtherLayers = true;
    o.clouds.otherLayerMap = true;
    const double shadow = relativeRmsLuminance(own.image, marched.image);
    EXPECT_GT(shadow, 0.1) << what;
    std::map<int, double> error;
    for (int size : {64, 256, 1024}) {
      o.clouds.otherLayerMapSize = size;
      const RenderResult map = test::cloudRenderer().render(s, o);
      expectFiniteNonNegative(map.image, what);
      error[size] = relativeRmsLuminance(map.image, marched.image);
    }
    o.clouds.otherLayerMapSize = 256;
    std::printf(
        "%s: the map against the marched crossings %.4f (64 texels), %.4f (256), %.4f (1024); the other layer's effect "
        "%.4f\n",
        what.c_str(), error[64], error[256], error[1024], shadow);
    EXPECT_LT(error[256], 0.05) << what;
    EXPECT_LT(error[1024], error[256]) << what;
    EXPECT_LT(error[256], error[64]) << what;
  }
}

// The deep shadow map (clouds/deep_shadow_map.glsl) against marching every light step: one layer
// (cumulus) and two (the map's second layer's slices), the sun high and low, looking up and towards the
// horizon, 64x36. The map keeps the march's first 3 steps (at least one of its level segments) and
// reads the rest of the way to the top. Measured relative RMS of the clouds' luminance: the default map
// (256 texels, 16 levels) 0.3-1.2 % from the march with the sun 35 degrees from the zenith and 1.0-3.5 %
// at 80 (neighbouring sun lines a texel apart pass through different heights of the layer when the sun
// is low), the fine map (512 texels, 32 levels) 0.2-1.8 %, about half the default's where that is over
// 2 % (1024 texels and 64 levels gave 0.2-0.9 % but cost 64x the default's bake: the test took 164 s
// with them, 31 s with these, in Release on lavapipe); the march itself is 0.2-0.6 % from one with 4x its light
// steps. Against the path tracer: CloudReference.SingleScatteringAgreesWithFirstOrder.
TEST_F(CloudRender, DeepShadowMapMatchesTheLightMarch) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 32;
  o.clouds.lightSteps = 6;
  const std::string twoLayers = mapTestTwoLayers();
  for (const std::string& layers : {test::cloudSceneText(), twoLayers})
    for (const auto& [what, s] : mapTestViews(layers)) {
      const std::string name = what + (layers == twoLayers ? ", two layers" : ", one layer");
      o.clouds.deepShadowMap = false;
      o.clouds.lightSteps = 24;
      const RenderResult marchedFine = test::cloudRenderer().render(s, o);
      o.clouds.lightSteps = 6;
      const RenderResult marched = test::cloudRenderer().render(s, o);
      o.clouds.deepShadowMap = true;
      const RenderResult map = test::cloudRenderer().render(s, o);
      o.clouds.deepShadowMapSize = 512;
      o.clouds.deepShadowMapLevels = 32;
      const RenderResult fine = test::cloudRenderer().render(s, o);
      o.clouds.deepShadowMapSize = 256;
      o.clouds.deepShadowMapLevels = 16;
      expectFiniteNonNegative(map.clouds, name);
      expectFiniteNonNegative(fine.clouds, name);
      const double error = relativeRmsLuminance(map.clouds, marched.clouds);
      const double fineError = relativeRmsLuminance(fine.clouds, marched.clouds);
      std::printf(
          "%s: the map against the march %.4f (256 texels, 16 levels), %.4f (512, 32); against the march with 4x light "
          "steps: march %.4f map %.4f fine map %.4f\n",
          name.c_str(), error, fineError, relativeRmsLuminance(marched.clouds, marchedFine.clouds),
          relativeRmsLuminance(map.clouds, marchedFine.clouds), relativeRmsLuminance(fine.clouds, marchedFine.clouds));
      EXPECT_LT(error, 0.05) << name;
      EXPECT_LT(fineError, 0.03) << name;
      EXPECT_LT(fineError, error) << name;
      if (error > 0.02) {  // where the texels dominate, the finer map halves it
        EXPECT_LT(fineError, 0.65 * error) << name;
      }
      EXPECT_GT(map.cloudSamples.mapPerPixel, 0.0) << name;
      EXPECT_LT(map.cloudSamples.lightPerPixel, marched.cloudSamples.lightPerPixel) << name;
    }
}

// The march converges: the error against a 1024-step render falls as the view steps grow (jitter off,
// so the error is the quadrature's, not noise).
TEST_F(CloudRender, ErrorFallsAsViewStepsGrow) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.jitter = false;
  o.clouds.coarseFactor = 1;
  Scene s = test::cloudScene({"/camera/width=32", "/camera/height=18"});
  o.clouds.viewSteps = 1024;
  const Image truth = test::cloudRenderer().render(s, o).clouds;
  std::vector<double> errors;
  for (int steps : {16, 64, 256}) {
    o.clouds.viewSteps = steps;
    const Image img = test::cloudRenderer().render(s, o).clouds;
    errors.push_back(relativeRmsLuminance(img, truth));
    std::printf("view steps %4d: relative RMS luminance error vs 1024 steps %.4f\n", steps, errors.back());
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
}

// The shipped thunderstorm scene (one cumulonimbus layer 1-12 km at the type's full extinction, its
// storm cells 10-50 km away, the weather simulation's map with 200 m cells) converges as the view
// steps grow. Measured at 80x45 against 1024 steps: 7.35 / 3.39 / 1.47 % at 64 / 128 / 256 steps with
// the empty-space test on the coverage reach, against 24.2 / 8.1 / 2.9 % with the margin
// test, whose bound the map's coverage jumps broke (docs/clouds.md "Empty-space skipping").
TEST_F(CloudRender, TallStormLayerConvergesAsViewStepsGrow) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.jitter = false;
  const Scene s =
      Scene::load(test::sourceDir() / "scenes" / "thunderstorm.json",
                  {"/weather/grid/cells_x=64", "/weather/grid/cells_y=64", "/camera/width=80", "/camera/height=45"});
  o.clouds.viewSteps = 1024;
  const Image truth = test::cloudRenderer().render(s, o).clouds;
  std::vector<double> errors;
  for (int steps : {64, 128, 256}) {
    o.clouds.viewSteps = steps;
    const Image img = test::cloudRenderer().render(s, o).clouds;
    errors.push_back(relativeRmsLuminance(img, truth));
    std::printf("thunderstorm, view steps %4d: relative RMS luminance error vs 1024 steps %.4f\n", steps,
                errors.back());
  }
  EXPECT_LT(errors[0], 0.12);
  EXPECT_LT(errors[1], 0.6 * errors[0]);
  EXPECT_LT(errors[2], 0.6 * errors[1]);
}

// Empty-space skipping must not lose cloud (docs/clouds.md, "Empty-space skipping"): the default march
// agrees with one that never skips (coarse factor 1) over the cloud pixels of the bench's sunset (a
// stratocumulus deck towards a sun 85 deg from the zenith, single scattering, so the thin fringes'
// forward scattering dominates). With the old test (margin 0) a span whose one shape sample just
// missed a fringe was skipped: -16 % in the bench's single scattering; here (48 x 27, shipped noise)
// measured 0.14 % rel RMSE (bias +0.06 %) for the default against 22 % (bias -4.6 %) for the old test.
TEST_F(CloudRender, EmptySpaceSkippingKeepsThinFringes) {
  const std::string text = test::cloudSceneText(
      R"({"kind": "stratocumulus", "bottom_m": 1000, "top_m": 2000, "coverage": 0.7, "extinction_scale": 0.3})");
  const Scene s =
      test::cloudScene({"/sun/zenith_deg=85", "/sun/azimuth_deg=270", "/camera/yaw_deg=270", "/camera/pitch_deg=25",
                        "/camera/fov_deg=70", "/camera/width=48", "/camera/height=27", "/clouds/lighting/ms_octaves=1"},
                       text);
  SkyRenderOptions o;  // the shipped noise sizes: the fringes are the 128^3 shape noise's
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = AerialPerspective::Off;
  auto cloudLuminance = [&](const SkyRenderOptions& options) {
    const Image img = test::cloudRenderer().render(s, options).clouds;
    std::vector<double> y(img.pixelCount());
    for (size_t i = 0; i < y.size(); ++i)
      y[i] = img.pixels[4 * i + 3] < 0.95f ? luminanceRec709(img.pixels.data() + 4 * i) : -1.0;
    return y;
  };
  SkyRenderOptions noSkip = o;
  noSkip.clouds.coarseFactor = 1;
  const std::vector<double> truth = cloudLuminance(noSkip);
  auto compare = [&](const std::vector<double>& y, double& bias) {
    double sum = 0.0, sumTruth = 0.0, sum2 = 0.0, ref2 = 0.0;
    for (size_t i = 0; i < y.size(); ++i) {
      if (truth[i] < 0.0) continue;
      const double v = std::max(y[i], 0.0);
      sum += v;
      sumTruth += truth[i];
      sum2 += (v - truth[i]) * (v - truth[i]);
      ref2 += truth[i] * truth[i];
    }
    bias = sum / std::max(sumTruth, 1e-30) - 1.0;
    return std::sqrt(sum2 / std::max(ref2, 1e-30));
  };
  double biasDefault = 0.0, biasOld = 0.0;
  const double errDefault = compare(cloudLuminance(o), biasDefault);
  SkyRenderOptions old = o;
  old.clouds.emptySpaceMargin = 0.0;
  const double errOld = compare(cloudLuminance(old), biasOld);
  std::printf("vs no skipping: default rel RMSE %.4f bias %+.4f; margin 0 %.4f bias %+.4f\n", errDefault, biasDefault,
              errOld, biasOld);
  EXPECT_LT(std::abs(biasDefault), 0.01);
  EXPECT_LT(errDefault, 0.02);
  EXPECT_GT(errOld, 5.0 * errDefault);  // the scene does show the fringes the old test lost
}

// The air in front of the clouds (docs/atmosphere.md, "Aerial-perspective volume"): the volume agrees
// with a 256-step per-pixel march of the same integrand over the cloud pixels, for a perspective, a
// fisheye and an equirectangular camera (measured at 640 x 360: 1.3e-4 to 8e-4 of the frame's
// luminance; here at 64 x 36, where the horizon and the sun take a larger share of the cloud pixels:
// 7.5e-4, 1.6e-3 (fisheye), 4.7e-4), leaving out the air is at least 10x worse (measured 45-165x),
// and only the volume mode runs the volume pass.
TEST_F(CloudRender, AerialVolumeAgreesWithAFineAirMarch) {
  for (const std::vector<std::string>& view :
       {std::vector<std::string>{"/camera/pitch_deg=8"},
        std::vector<std::string>{"/camera/projection=fisheye", "/camera/fov_deg=180", "/camera/pitch_deg=90"},
        std::vector<std::string>{"/camera/projection=equirectangular", "/camera/pitch_deg=0"}}) {
    const Scene s = test::cloudScene(view);
    auto render = [&](AerialPerspective mode, int steps) {
      SkyRenderOptions o = test::smallCloudOptions();
      o.clouds.aerialPerspective = mode;
      o.clouds.aerialPerspectiveSteps = steps;
      return test::cloudRenderer().render(s, o);
    };
    const RenderResult fine = render(AerialPerspective::March, 256);
    const RenderResult volume = render(AerialPerspective::Volume, 8);
    const RenderResult off = render(AerialPerspective::Off, 8);
    std::vector<float> mask(fine.clouds.pixelCount());
    size_t cloudPixels = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
      mask[i] = fine.clouds.pixels[4 * i + 3] < 0.95f ? 1.0f : 0.0f;
      cloudPixels += mask[i] > 0.0f;
    }
    ASSERT_GT(cloudPixels, 50u) << view.front();
    const double volumeError = compareImages(volume.image, fine.image, mask).luminance.relativeRmse;
    const double offError = compareImages(off.image, fine.image, mask).luminance.relativeRmse;
    std::printf("%s: aerial perspective volume %.2e, off %.2e (rel RMSE over %zu cloud pixels vs the 256-step march)\n",
                view.front().c_str(), volumeError, offError, cloudPixels);
    EXPECT_LT(volumeError, 3e-3) << view.front();
    EXPECT_GT(offError, 10.0 * volumeError) << view.front();
    auto ran = [](const RenderResult& r) {
      for (const auto& t : r.timings)
        if (t.label == "sky/aerial_perspective_volume") return true;
      return false;
    };
    EXPECT_TRUE(ran(volume));
    EXPECT_FALSE(ran(fine));
    EXPECT_FALSE(ran(off));
    expectFiniteNonNegative(volume.image, view.front());
  }
}

// The default scene (cumulus at 12 degrees pitch, here 80x45 with the tests' small noise): the uniform
// split (total length / N) gives steps of up to ~1 km at the horizon; steps growing with distance
// (common/cloud_march.glsl) spend the samples where the clouds are near and large on screen. At the
// same N = 64 (jitter and skipping off) the growing schedule's error against a converged render
// (uniform, 2048 steps) is smaller by more than a third, at less than 1.5x the samples.
TEST_F(CloudRender, GrowingStepsBeatUniformSteps) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.jitter = false;
  o.clouds.coarseFactor = 1;
  const Scene s = Scene::load(test::sourceDir() / "scenes" / "cumulus.json", {"/camera/width=80", "/camera/height=45"});
  o.clouds.viewSteps = 2048;
  o.clouds.uniformSteps = true;
  const RenderResult truth = test::cloudRenderer().render(s, o);
  o.clouds.viewSteps = 64;
  const RenderResult uniform = test::cloudRenderer().render(s, o);
  o.clouds.uniformSteps = false;
  const RenderResult growing = test::cloudRenderer().render(s, o);
  const double eGrowing = relativeRmsLuminance(growing.clouds, truth.clouds);
  const double eUniform = relativeRmsLuminance(uniform.clouds, truth.clouds);
  std::printf("64 view steps: relative RMS error growing %.4f (%.1f samples/pixel), uniform %.4f (%.1f)\n", eGrowing,
              growing.cloudSamples.viewPerPixel, eUniform, uniform.cloudSamples.viewPerPixel);
  EXPECT_LT(eGrowing, 0.66 * eUniform);
  EXPECT_LT(growing.cloudSamples.viewPerPixel, 1.5 * uniform.cloudSamples.viewPerPixel);
  EXPECT_GT(uniform.cloudSamples.viewPerPixel, 0.0);
}

TEST(CloudSettingsTest, RejectsOctavesThatAddEnergyAndOverlaps) {
  EXPECT_THROW(CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/ms_a=0.8", "/clouds/lighting/ms_b=0.5"})),
               InputError);
  EXPECT_THROW(
      CloudSettings::fromScene(test::cloudScene(
          {}, test::cloudSceneText(R"({"bottom_m": 1000, "top_m": 3000}, {"bottom_m": 2000, "top_m": 5000})"))),
      InputError);
  EXPECT_THROW(CloudSettings::fromScene(test::cloudScene({"/clouds/layers/0/top_m=1000"})), InputError);
  // ms_a alone is checked against the layer type's calibrated b for the scene's phase (cumulus with the
  // approximate Mie phase: b = 0.677; every dual-HG type's b is 1).
  const double cumulusMieB = cloudTypeMultipleScattering(shared::kCloudCumulus, CloudPhaseModel::ApproximateMie).b;
  ASSERT_LT(cumulusMieB, 0.99);
  const std::string mie = "/clouds/lighting/phase=approximate_mie";
  EXPECT_THROW(
      CloudSettings::fromScene(test::cloudScene({mie, "/clouds/lighting/ms_a=" + std::to_string(cumulusMieB + 0.01)})),
      InputError);
  EXPECT_NO_THROW(
      CloudSettings::fromScene(test::cloudScene({mie, "/clouds/lighting/ms_a=" + std::to_string(cumulusMieB - 0.01)})));
}

// Octave parameters: the type's calibrated values per layer unless the scene gives them (then for all).
TEST(CloudSettingsTest, OctaveParametersPerTypeUnlessGiven) {
  const std::string twoLayers = test::cloudSceneText(
      R"({"kind": "stratocumulus", "bottom_m": 800, "top_m": 1400}, {"kind": "cumulus", "bottom_m": 1500, "top_m": 3000})");
  const CloudSettings typed = CloudSettings::fromScene(test::cloudScene({}, twoLayers));
  ASSERT_EQ(typed.layers.size(), 2u);
  const CloudMultipleScattering sc = cloudTypeMultipleScattering(shared::kCloudStratocumulus);
  const CloudMultipleScattering cu = cloudTypeMultipleScattering(shared::kCloudCumulus);
  EXPECT_EQ(typed.layers[0].msA, sc.a);
  EXPECT_EQ(typed.layers[0].msC, sc.c);
  EXPECT_EQ(typed.layers[1].msB, cu.b);
  EXPECT_EQ(typed.layers[1].msC, cu.c);
  EXPECT_EQ(typed.layers[0].msD, sc.d);
  EXPECT_EQ(typed.layers[1].msD, cu.d);
  EXPECT_NE(sc.c, cu.c);
  for (CloudPhaseModel phase : {CloudPhaseModel::DualHenyeyGreenstein, CloudPhaseModel::ApproximateMie})
    for (int kind = 0; kind <= shared::kCloudCirrus; ++kind) {
      const CloudMultipleScattering m = cloudTypeMultipleScattering(kind, phase);
      EXPECT_LE(m.a, m.b) << kind;  // the energy bound of the octaves
      EXPECT_LE(m.b, 1.0) << kind;
      EXPECT_GE(m.d, 0.0) << kind;  // the diffusion floor's weight: 0 (off) to 2 (the schema's range)
      EXPECT_LE(m.d, 2.0) << kind;
    }
  // The approximate Mie phase takes its own fit.
  const CloudSettings mie =
      CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/phase=approximate_mie"}, twoLayers));
  EXPECT_EQ(mie.layers[1].msA, cloudTypeMultipleScattering(shared::kCloudCumulus, CloudPhaseModel::ApproximateMie).a);
  EXPECT_NE(mie.layers[1].msA, cu.a);
  const CloudSettings given = CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/ms_c=0.7"}, twoLayers));
  EXPECT_EQ(given.layers[0].msC, 0.7);
  EXPECT_EQ(CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/ms_d=0"}, twoLayers)).layers[1].msD, 0.0);
  EXPECT_THROW(CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/ms_d=3"}, twoLayers)), InputError);
  EXPECT_EQ(given.layers[1].msC, 0.7);
  EXPECT_EQ(given.layers[0].msB, sc.b);
  // The low-sun scale's mu_0: cumulus's fit, none for stratocumulus; the scene's for every layer.
  EXPECT_EQ(typed.layers[1].msLowSunMu, cu.lowSunMu);
  EXPECT_GT(cu.lowSunMu, 0.0);
  EXPECT_EQ(typed.layers[0].msLowSunMu, sc.lowSunMu);
  const CloudSettings lowSunGiven =
      CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/ms_low_sun_mu=0.2"}, twoLayers));
  EXPECT_EQ(lowSunGiven.layers[0].msLowSunMu, 0.2);
  EXPECT_EQ(lowSunGiven.layers[1].msLowSunMu, 0.2);
  EXPECT_THROW(CloudSettings::fromScene(test::cloudScene({"/clouds/lighting/ms_low_sun_mu=1.5"}, twoLayers)),
               InputError);
}

// The quality presets change the march's steps only. The octave parameters are fitted for 3 octaves: a
// 4th adds about +48 % at noon (docs/clouds.md, bench "octaves" rows), and a `low` with 2 octaves
// made two_layers -52 % against the path tracer (docs/clouds.md "Quality presets").
TEST(CloudSettingsTest, QualityPresetsKeepTheFittedOctaves) {
  const CloudSettings standard = CloudSettings::fromScene(test::cloudScene({}));
  const CloudSettings low = CloudSettings::fromScene(test::cloudScene({"/clouds/quality=\"low\""}));
  const CloudSettings high = CloudSettings::fromScene(test::cloudScene({"/clouds/quality=\"high\""}));
  EXPECT_EQ(standard.lighting.octaves, 3);
  EXPECT_EQ(standard.march.viewSteps, 64);
  EXPECT_EQ(standard.march.lightSteps, 6);
  EXPECT_EQ(low.march.viewSteps, 32);
  EXPECT_EQ(low.march.lightSteps, 4);
  EXPECT_EQ(low.lighting.octaves, standard.lighting.octaves);
  EXPECT_EQ(high.march.viewSteps, 128);
  EXPECT_EQ(high.march.lightSteps, 8);
  EXPECT_EQ(high.lighting.octaves, standard.lighting.octaves);
  EXPECT_THROW(CloudSettings::fromScene(test::cloudScene({"/clouds/quality=\"ultra\""})), InputError);
}

}  // namespace
}  // namespace firmament
