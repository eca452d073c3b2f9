// The GPU march against the CPU path tracer on one small cumulus scene (same density from the same
// textures, same phase function, same sun through the atmosphere). Ambient light and aerial
// perspective are off in both, so the comparison isolates the cloud transport of sunlight: the
// march's octave multiple-scattering approximation against all orders.
#include <gtest/gtest.h>

#include <cmath>

#include "clouds/reference_clouds.h"
#include "core/color.h"
#include "sky/scene_weather.h"
#include "tests/clouds/cloud_test_support.h"

namespace firmament {
namespace {

class CloudReference : public test::GpuTest {};

TEST_F(CloudReference, GpuMarchAgainstPathTracer) {
  // A thinner cumulus (extinction x 0.2: sigma_t <= 0.02 m^-1) keeps the paths short enough for a test.
  Scene scene = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
                                  "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500"});
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 256;
  o.clouds.lightSteps = 16;
  o.clouds.jitter = false;
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = false;
  RenderResult gpu = test::cloudRenderer().render(scene, o);

  CloudSettings settings = CloudSettings::fromScene(scene);
  // The same textures: bake with the same seed and sizes, read back.
  CloudNoise noise(context());
  gpu::CommandList commands(context());
  noise.update(settings.seed, o.cloudNoise, commands);
  commands.submitAndWait();
  const SceneView& view = gpu.view;
  const double ground = view.cameraRadius - scene.number("/camera/height_above_ground_m");
  CloudMedium medium(sharedCloudLayers(settings, ground), noise.downloadShape(), noise.downloadDetail(),
                     noise.downloadCurl(), cloudWeatherMapForScene(scene), ground);
  CloudReferenceSettings rs;
  rs.samplesPerPixel = 48;
  CloudPathTracer tracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{}, rs);
  CloudReferenceImage ref = renderCloudReference(tracer, glm::dvec3(0.0, 0.0, view.cameraRadius), view.camera, 0);

  double sum2 = 0.0, ref2 = 0.0, gpuSum = 0.0, refSum = 0.0, se2 = 0.0, tDiff = 0.0;
  int cloudPixels = 0;
  for (size_t i = 0; i < ref.image.pixelCount(); ++i) {
    const double t = ref.image.pixels[4 * i + 3];
    tDiff = std::max(tDiff, std::abs(t - double(gpu.clouds.pixels[4 * i + 3])));
    if (t > 0.95) continue;
    const double yRef = ref.luminance[i];
    const double yGpu = luminanceRec709(gpu.clouds.pixels.data() + 4 * i);
    sum2 += (yGpu - yRef) * (yGpu - yRef);
    ref2 += yRef * yRef;
    gpuSum += yGpu;
    refSum += yRef;
    se2 += ref.luminanceStandardError[i] * ref.luminanceStandardError[i];
    ++cloudPixels;
  }
  ASSERT_GT(cloudPixels, 20);
  const double relRmse = std::sqrt(sum2 / ref2);
  const double meanSe = std::sqrt(se2) / cloudPixels;
  std::printf("cloud pixels %d: rel RMSE of luminance %.3f; mean GPU %.1f, path tracer %.1f +- %.1f cd/m^2 "
              "(%.2f s, %lld events); max |T_gpu - T_ref| %.3f\n",
              cloudPixels, relRmse, gpuSum / cloudPixels, refSum / cloudPixels, meanSe, ref.seconds, ref.events, tDiff);
  // Transmittance is the same integral in both (the march's quadrature vs unbiased ratio tracking).
  EXPECT_LT(tDiff, 0.08);  // 48 ratio-tracking estimates per pixel: noise ~0.02
  // Albedo 1, no energy gain: the march's mean over the cloud is below the path tracer's plus 10 %
  // (the octave approximation may not exceed all orders of scattering by more than that) and 3 SE.
  EXPECT_LE(gpuSum / cloudPixels, 1.1 * refSum / cloudPixels + 3.0 * meanSe);
  EXPECT_LT(relRmse, 0.6);
}

}  // namespace
}  // namespace firmament
