// No energy gain: with a white ground (albedo 1) and no absorption (no ozone, aerosol single-scattering
// albedo 1) the fast path must not be brighter than the reference path tracer, which conserves energy
// exactly (tests/atmosphere, reference energy test). Compared over the whole sphere of directions
// (equirectangular), mean luminance, with a tolerance of 3 reference standard errors plus 3 %.
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/reference_renderer.h"
#include "core/color.h"
#include "sky/scene_view.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class SkyEnergyTest : public test::GpuTest {};

TEST_F(SkyEnergyTest, WhiteGroundNoAbsorptionGainsNoEnergy) {
  for (const char* zenith : {"30", "80"}) {
    Scene scene = Scene::parse(
        "{}", "<test>",
        {"/atmosphere/ground_albedo=1", "/atmosphere/ozone/column_dobson=0",
         "/atmosphere/mie/single_scattering_albedo=1", std::string("/sun/zenith_deg=") + zenith,
         "/camera/projection=equirectangular", "/camera/width=16", "/camera/height=8", "/location/height_m=0"});
    SkyRenderer renderer(context());
    RenderResult fast = renderer.render(scene);

    SceneView view = makeSceneView(scene);
    ReferenceQuality quality;
    quality.samplesPerPixel = 64;
    quality.wavelengthCount = 24;
    ReferenceRenderer reference(view.atmosphere, view.sunDirection, quality);
    ReferenceImage truth = renderReferenceImage(reference, view.cameraRadius, view.camera);

    double fastSum = 0.0, referenceSum = 0.0, variance = 0.0;
    for (size_t i = 0; i < fast.image.pixelCount(); ++i) {
      fastSum += luminanceRec709(fast.image.pixels.data() + 4 * i);
      referenceSum += truth.luminance[i];
      variance += truth.luminanceStandardError[i] * truth.luminanceStandardError[i];
    }
    const double n = double(fast.image.pixelCount());
    const double standardError = std::sqrt(variance) / n;
    EXPECT_LE(fastSum / n, referenceSum / n * 1.03 + 3.0 * standardError) << "sun zenith " << zenith;
    std::printf("sun zenith %s: fast %.1f, reference %.1f +- %.1f cd/m2\n", zenith, fastSum / n, referenceSum / n,
                standardError);
  }
}

}  // namespace
}  // namespace firmament

namespace firmament {
namespace {

// No seam where the method switches: just inside the top of the atmosphere the sky-view table path
// and the per-pixel march (which takes over above the top) agree, and both are continuous across it.
TEST_F(SkyEnergyTest, NoSeamAtTheTopOfTheAtmosphere) {
  SkyRenderer renderer(context());
  auto render = [&](double altitude, SkyMethod method) {
    Scene scene =
        Scene::parse("{}", "<test>",
                     {"/location/height_m=0", "/camera/height_above_ground_m=" + std::to_string(altitude),
                      "/camera/pitch_deg=-10", "/sun/zenith_deg=50", "/camera/width=24", "/camera/height=16"});
    SkyRenderOptions options;
    options.method = method;
    RenderResult r = renderer.render(scene, options);
    double sum = 0.0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) sum += luminanceRec709(r.image.pixels.data() + 4 * i);
    return std::make_pair(sum / double(r.image.pixelCount()), r.methodUsed);
  };
  auto [inside, insideMethod] = render(59990.0, SkyMethod::SkyViewLut);
  auto [insideMarch, marchMethod] = render(59990.0, SkyMethod::PerPixel);
  auto [above, aboveMethod] = render(60010.0, SkyMethod::SkyViewLut);
  EXPECT_EQ(insideMethod, SkyMethod::SkyViewLut);
  EXPECT_EQ(aboveMethod, SkyMethod::PerPixel);
  EXPECT_NEAR(inside, insideMarch, 0.01 * insideMarch);
  EXPECT_NEAR(inside, above, 0.01 * above);
}

}  // namespace
}  // namespace firmament
