// Multiple scattering at a low sun against the reference path tracer, 12 wavelengths so that colour
// conversion is not the error.
// - Sunset, the bench's view (sun zenith 88 deg, looking 50 deg beside it along the horizon). Hillaire
//   2020's form (one order, isotropic phase) measures a -3.6 % luminance bias here (the test prints
//   both; docs/atmosphere.md: its multiple scattering is 16-22 % short at this sun). The shipped form
//   (3 orders, anisotropy) must be within 1.5 % plus 3 standard errors of the reference's mean, and at
//   most half as biased as Hillaire's.
// - Twilight (sun 6 deg below the horizon, looking at the glow): multiple scattering is 10-23 % of the
//   light and falls by orders of magnitude across the Earth's shadow. With the table interpolated
//   linearly the mean was +14 % (multiple scattering about twice the reference's); interpolated as a
//   logarithm it measured +3 %. Bound: 6 % plus 3 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "atmosphere/reference_renderer.h"
#include "core/color.h"
#include "sky/scene_view.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class MultipleScatteringAccuracyTest : public test::GpuTest {};

struct ReferenceMean {
  double mean = 0.0;           // mean luminance over the image, cd/m2
  double standardError = 0.0;  // of that mean (the path tracer's noise)
};

ReferenceMean referenceMean(const Scene& scene, int samplesPerPixel) {
  SceneView view = makeSceneView(scene);
  ReferenceQuality quality;
  quality.samplesPerPixel = samplesPerPixel;
  quality.wavelengthCount = 24;
  ReferenceRenderer reference(view.atmosphere, view.sunDirection, quality);
  ReferenceImage truth = renderReferenceImage(reference, view.cameraRadius, view.camera);
  double sum = 0.0, variance = 0.0;
  for (size_t i = 0; i < truth.luminance.size(); ++i) {
    sum += truth.luminance[i];
    variance += truth.luminanceStandardError[i] * truth.luminanceStandardError[i];
  }
  const double n = double(truth.luminance.size());
  return {sum / n, std::sqrt(variance) / n};
}

// Mean luminance of the fast path over the reference's, minus one.
double meanBias(gpu::Context& context, const Scene& scene, const ReferenceMean& truth, int orders) {
  SkyRenderer renderer(context);
  SkyRenderOptions options;
  options.luts.spectralSamples = 12;
  options.luts.multipleScatteringOrders = orders;
  RenderResult fast = renderer.render(scene, options);
  double sum = 0.0;
  for (size_t i = 0; i < fast.image.pixelCount(); ++i) sum += luminanceRec709(fast.image.pixels.data() + 4 * i);
  return sum / double(fast.image.pixelCount()) / truth.mean - 1.0;
}

TEST_F(MultipleScatteringAccuracyTest, LowSunAgreesWithThePathTracer) {
  Scene scene = Scene::parse("{}", "<test>",
                             {"/sun/zenith_deg=88", "/sun/azimuth_deg=270", "/camera/yaw_deg=220",
                              "/camera/pitch_deg=8", "/camera/width=24", "/camera/height=14"});
  const ReferenceMean truth = referenceMean(scene, 256);
  const double hillaire = meanBias(context(), scene, truth, 1);
  const double shipped = meanBias(context(), scene, truth, SkyRenderOptions{}.luts.multipleScatteringOrders);
  std::printf("sunset mean luminance bias: Hillaire 2020 %+.2f %%, shipped %+.2f %% (reference %.1f +- %.1f cd/m2)\n",
              100.0 * hillaire, 100.0 * shipped, truth.mean, truth.standardError);
  EXPECT_LT(std::abs(shipped), 0.015 + 3.0 * truth.standardError / truth.mean);
  EXPECT_LT(std::abs(shipped), 0.5 * std::abs(hillaire));
}

TEST_F(MultipleScatteringAccuracyTest, TwilightAgreesWithThePathTracer) {
  Scene scene = Scene::parse("{}", "<test>",
                             {"/sun/zenith_deg=96", "/sun/azimuth_deg=270", "/camera/yaw_deg=270",
                              "/camera/pitch_deg=8", "/camera/width=24", "/camera/height=14"});
  const ReferenceMean truth = referenceMean(scene, 256);
  const double shipped = meanBias(context(), scene, truth, SkyRenderOptions{}.luts.multipleScatteringOrders);
  std::printf("twilight mean luminance bias: shipped %+.2f %% (reference %.2f +- %.2f cd/m2)\n", 100.0 * shipped,
              truth.mean, truth.standardError);
  EXPECT_LT(std::abs(shipped), 0.06 + 3.0 * truth.standardError / truth.mean);
}

}  // namespace
}  // namespace firmament
