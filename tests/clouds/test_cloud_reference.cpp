// The GPU march against the CPU path tracer on one small cumulus scene (same density from the same
// textures, same phase function, same sun through the atmosphere). Ambient light and aerial
// perspective are off in both, so the comparison isolates the cloud transport of sunlight: the
// march's octave multiple-scattering approximation against all orders; and the single scattering
// alone against the path tracer's first order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "clouds/cloud_noise.h"
#include "clouds/reference_clouds.h"
#include "core/color.h"
#include "sky/scene_weather.h"
#include "tests/clouds/cloud_test_support.h"

namespace firmament {
namespace {

class CloudReference : public test::GpuTest {};

// The path tracer's medium for a scene the GPU rendered with `options`: the same noise texels (baked
// with the same seed and sizes, read back) and the same weather map.
CloudMedium cloudMediumFor(gpu::Context& context, const Scene& scene, const CloudSettings& settings,
                           const SkyRenderOptions& options, const SceneView& view) {
  CloudNoise noise(context);
  gpu::CommandList commands(context);
  noise.update(settings.seed, options.cloudNoise, commands);
  commands.submitAndWait();
  const double ground = view.cameraRadius - scene.number("/camera/height_above_ground_m");
  return CloudMedium(sharedCloudLayers(settings, ground), noise.downloadShape(), noise.downloadDetail(), noise.downloadCurl(),
                     cloudWeatherMapForScene(scene), ground);
}

// A thinner cumulus (extinction x 0.2: sigma_t <= 0.02 m^-1) keeps the paths short enough for a test.
Scene thinCumulusScene() {
  return test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
                           "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500"});
}

// A fine march (256 view, 16 light steps, no jitter), sunlight alone, no air in front.
SkyRenderOptions fineMarchOptions() {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 256;
  o.clouds.lightSteps = 16;
  o.clouds.jitter = false;
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = AerialPerspective::Off;
  return o;
}

TEST_F(CloudReference, GpuMarchAgainstPathTracer) {
  Scene scene = thinCumulusScene();
  SkyRenderOptions o = fineMarchOptions();
  RenderResult gpu = test::cloudRenderer().render(scene, o);

  CloudSettings settings = CloudSettings::fromScene(scene);
  const SceneView& view = gpu.view;
  const CloudMedium medium = cloudMediumFor(context(), scene, settings, o, view);
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
  const CloudReferenceError e = compareWithCloudReference(gpu.clouds, ref);
  std::printf("cloud pixels %d: rel RMSE of luminance %.3f (reference noise %.3f, noise-corrected %.3f); mean GPU "
              "%.1f, path tracer %.1f +- %.1f cd/m^2 (bias %+.3f; %.2f s, %lld events); max |T_gpu - T_ref| %.3f\n",
              cloudPixels, relRmse, e.noiseFloor, e.noiseCorrected, gpuSum / cloudPixels, refSum / cloudPixels, meanSe,
              e.meanBias, ref.seconds, ref.events, tDiff);
  // Transmittance is the same integral in both (the march's quadrature vs unbiased ratio tracking).
  EXPECT_LT(tDiff, 0.08);  // 48 ratio-tracking estimates per pixel: noise ~0.02
  // Albedo 1, no large energy gain: with the calibrated per-type octaves (docs/clouds.md, "Calibration")
  // this thin, smooth cumulus (32^3 noise, extinction x 0.2: outside the calibration set) comes out
  // 15 % brighter than all orders (measured: 6515 vs 5681 +- 110); the first milestone's octaves were
  // 12 % darker. Bound: 1.25 x the path tracer + 3 SE.
  EXPECT_LE(gpuSum / cloudPixels, 1.25 * refSum / cloudPixels + 3.0 * meanSe);
  EXPECT_GE(gpuSum / cloudPixels, 0.85 * refSum / cloudPixels - 3.0 * meanSe);
  EXPECT_LT(relRmse, 0.45);  // measured 0.367 (0.378 with the first milestone's lighting)
}

// The ambient (sky and ground light; docs/clouds.md "Lighting") against paths that see a constant sky
// and a Lambertian ground where they leave the shells: the light each side gains from them, over the
// cloud pixels of the scene above. The fast path's sky irradiance comes from its tables at each sample,
// the path tracer's from the clear-sky reference at the layer's mid-height.
TEST_F(CloudReference, AmbientAgainstPathTracerWithSkyAndGround) {
  const Scene scene = thinCumulusScene();
  SkyRenderOptions o = fineMarchOptions();
  const RenderResult sunOnly = test::cloudRenderer().render(scene, o);
  o.clouds.ambient = true;
  const RenderResult withAmbient = test::cloudRenderer().render(scene, o);

  const CloudSettings settings = CloudSettings::fromScene(scene);
  const SceneView& view = sunOnly.view;
  const CloudMedium medium = cloudMediumFor(context(), scene, settings, o, view);
  CloudReferenceSettings rs;
  rs.samplesPerPixel = 48;
  const double ground = view.cameraRadius - scene.number("/camera/height_above_ground_m");
  const double middle = 0.5 * (settings.layers[0].bottom_m + settings.layers[0].top_m);
  const CloudEnvironment environment = cloudEnvironmentFromReference(view.atmosphere, view.sunDirection, ground + middle);
  const CloudPathTracer sunTracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{}, rs);
  const CloudPathTracer skyTracer(medium, settings.lighting, view.atmosphere, view.sunDirection, environment, rs);
  const glm::dvec3 camera(0.0, 0.0, view.cameraRadius);
  const CloudReferenceImage refSun = renderCloudReference(sunTracer, camera, view.camera, 0);
  const CloudReferenceImage refSky = renderCloudReference(skyTracer, camera, view.camera, 0);

  double gpuGain = 0.0, refGain = 0.0, gpuSun = 0.0, refSun2 = 0.0, se2 = 0.0;
  int cloudPixels = 0;
  for (size_t i = 0; i < refSun.image.pixelCount(); ++i) {
    if (refSun.image.pixels[4 * i + 3] > 0.95) continue;
    const double on = luminanceRec709(withAmbient.clouds.pixels.data() + 4 * i);
    const double off = luminanceRec709(sunOnly.clouds.pixels.data() + 4 * i);
    ASSERT_TRUE(std::isfinite(on));
    EXPECT_GE(on, off * (1.0 - 1e-5));  // the ambient only adds light
    gpuGain += on - off;
    gpuSun += off;
    refGain += refSky.luminance[i] - refSun.luminance[i];
    refSun2 += refSun.luminance[i];
    se2 += refSky.luminanceStandardError[i] * refSky.luminanceStandardError[i] +
           refSun.luminanceStandardError[i] * refSun.luminanceStandardError[i];
    ++cloudPixels;
  }
  ASSERT_GT(cloudPixels, 20);
  const double gainSe = std::sqrt(se2);  // of the summed gain (the two references' noise is independent)
  std::printf("cloud pixels %d: the ambient adds %.1f cd/m^2 a pixel on the GPU, %.1f +- %.1f in the path tracer "
              "(ratio %.3f); sunlight alone %.1f and %.1f\n",
              cloudPixels, gpuGain / cloudPixels, refGain / cloudPixels, gainSe / cloudPixels, gpuGain / refGain,
              gpuSun / cloudPixels, refSun2 / cloudPixels);
  EXPECT_GT(refGain, 3.0 * gainSe);  // the sky's light is resolved by the references
  // Measured 1802 against 1591 +- 158 a pixel (ratio 1.13; 1377, 0.87, with the ambient by height of
  // sessions 1-24: CloudMarchSettings::ambientSlab false). Bound: within 25 % + 3 SE, which a missing
  // ambient (0) or a doubled one (3600) fails.
  EXPECT_LE(std::abs(gpuGain - refGain), 0.25 * refGain + 3.0 * gainSe);
}

// The GPU march's single scattering (one octave, no cone) against the path tracer limited to one
// scattering event: the same integral, so they must agree to within the reference's noise and the
// march's quadrature. Two scenes: the cumulus above (sun 40 deg), and a stratocumulus slab under a sun
// 85 deg from the zenith, looked at towards the sun, where the sun ray crosses ~10 km of cloud: the
// first milestone's light march over one layer thickness saw a fraction of that optical depth.
struct SingleScatteringResult {
  CloudReferenceError march, fixedLength, ownLayerOnly;
  double meanStandardError = 0.0;  // of the reference's mean over the cloud pixels, relative
};

SingleScatteringResult singleScattering(gpu::Context& context, const Scene& scene, int samplesPerPixel) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.viewSteps = 256;
  o.clouds.lightSteps = 16;
  o.clouds.lightCone = 0.0;
  o.clouds.jitter = false;
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = AerialPerspective::Off;
  // The first order is never δ-scaled (scaling folds the peak's forward multiple scattering into the
  // first order), so neither is the march here; it changes nothing for dual HG.
  o.clouds.deltaScaling = false;
  const RenderResult gpu = test::cloudRenderer().render(scene, o);
  o.clouds.lightThroughOtherLayers = false;
  const RenderResult ownLayerOnly = test::cloudRenderer().render(scene, o);
  o.clouds.lightThroughOtherLayers = true;
  o.clouds.lightMarchToExit = false;
  const RenderResult fixedLength = test::cloudRenderer().render(scene, o);
  const CloudSettings settings = CloudSettings::fromScene(scene);
  const SceneView& view = gpu.view;
  const CloudMedium medium = cloudMediumFor(context, scene, settings, o, view);
  CloudReferenceSettings rs;
  rs.samplesPerPixel = samplesPerPixel;
  rs.maxScatteringOrder = 1;
  CloudPathTracer tracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{}, rs);
  CloudReferenceImage ref = renderCloudReference(tracer, glm::dvec3(0.0, 0.0, view.cameraRadius), view.camera, 0);
  SingleScatteringResult r;
  r.march = compareWithCloudReference(gpu.clouds, ref);
  r.fixedLength = compareWithCloudReference(fixedLength.clouds, ref);
  r.ownLayerOnly = compareWithCloudReference(ownLayerOnly.clouds, ref);
  double se2 = 0.0;
  for (size_t i = 0; i < ref.image.pixelCount(); ++i)
    if (ref.image.pixels[4 * i + 3] < 0.95) se2 += ref.luminanceStandardError[i] * ref.luminanceStandardError[i];
  r.meanStandardError = r.march.pixels > 0 ? std::sqrt(se2) / r.march.pixels / r.march.meanReference : 0.0;
  std::printf("single scattering, %d cloud pixels: rel RMSE %.3f (noise %.3f, corrected %.3f), mean %.1f vs %.1f "
              "(bias %+.3f, reference SE of the mean %.3f); milestone 1's fixed-length light march: bias %+.3f; own layer "
              "only: corrected %.3f, bias %+.3f\n",
              r.march.pixels, r.march.relRmse, r.march.noiseFloor, r.march.noiseCorrected, r.march.meanTest,
              r.march.meanReference, r.march.meanBias, r.meanStandardError, r.fixedLength.meanBias,
              r.ownLayerOnly.noiseCorrected, r.ownLayerOnly.meanBias);
  return r;
}

TEST_F(CloudReference, SingleScatteringAgreesWithFirstOrder) {
  const Scene cumulus = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
                                          "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500", "/clouds/lighting/ms_octaves=1"});
  const SingleScatteringResult noon = singleScattering(context(), cumulus, 64);
  ASSERT_GT(noon.march.pixels, 20);
  EXPECT_LT(std::abs(noon.march.meanBias), 0.03 + 3.0 * noon.meanStandardError);
  EXPECT_LT(noon.march.noiseCorrected, 0.08);

  const Scene sunset = test::cloudScene(
      {"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14", "/camera/pitch_deg=25",
       "/camera/yaw_deg=270", "/sun/zenith_deg=85", "/sun/azimuth_deg=270", "/clouds/lighting/ms_octaves=1"},
      test::cloudSceneText(R"({"kind": "stratocumulus", "bottom_m": 1000, "top_m": 2000, "coverage": 0.5})"));
  const SingleScatteringResult low = singleScattering(context(), sunset, 256);
  ASSERT_GT(low.march.pixels, 20);
  EXPECT_LT(std::abs(low.march.meanBias), 0.05 + 3.0 * low.meanStandardError);
  EXPECT_LT(low.march.noiseCorrected, 0.15);
  // The check can fail: the first milestone's light march (one layer thickness) is far too bright here.
  EXPECT_GT(low.fixedLength.meanBias, 0.5);
}

// Two decks, the camera under both: the sun ray from the lower deck crosses the upper one, which the
// path tracer's medium has. The march's light through the other layers must agree with the first
// order within the noon bounds above (measured -3.8 %, noise-corrected 0.081); marching the sample's
// own layer only leaves the lower deck unshadowed, far too bright (measured +412 %: the check can fail).
// The upper deck is kept thin (extinction x 0.1): where the sun ray's optical depth reaches ~10 (x 0.2
// here) the march's early exit at T = 0.01 cuts ~20 % of the first order, with one layer as with two
// (docs/clouds.md, "Lighting": light through other layers).
TEST_F(CloudReference, ADeckAboveShadowsTheLayerBelow) {
  const Scene decks = test::cloudScene(
      {"/clouds/layers/0/extinction_scale=0.2", "/clouds/layers/1/extinction_scale=0.1", "/camera/width=24", "/camera/height=14",
       "/camera/pitch_deg=60", "/clouds/lighting/ms_octaves=1"},
      test::cloudSceneText(R"({"kind": "stratocumulus", "bottom_m": 1000, "top_m": 1800, "coverage": 0.45},
                              {"kind": "stratocumulus", "bottom_m": 2600, "top_m": 3400, "coverage": 0.6})"));
  const SingleScatteringResult r = singleScattering(context(), decks, 256);
  ASSERT_GT(r.march.pixels, 20);
  EXPECT_LT(std::abs(r.march.meanBias), 0.05 + 3.0 * r.meanStandardError);
  EXPECT_LT(r.march.noiseCorrected, 0.15);
  EXPECT_GT(r.ownLayerOnly.meanBias, 1.0);
}

// Cumulus under a stratocumulus deck, all orders, the shipped model (3 octaves, the type fits, the
// reflected light), sunlight only: the light that reaches the cumulus through the deck is mostly
// scattered, ~1/tau of the flux for a thick deck, which the octaves' e^(-a^i tau) alone lose. With the
// deck's diffuse light (cloudOctaveTransmittanceThroughOthers) the bench's two_layers is -0.2 %; without
// it, -21 % (session 19, the cumulus fit with a = 0.445). This scene (like the bench's, other seed and
// sun) measured -5.2 % with it and -14.1 % without (a scratch build; the reference's standard error of
// the mean 1.9 %). Bound: 8 % + 2 standard errors (11.8 %).
TEST_F(CloudReference, ALayerUnderADeckKeepsTheDecksDiffuseLight) {
  const Scene scene = Scene::parse(
      R"({"location": {"height_m": 300}, "sun": {"zenith_deg": 30, "azimuth_deg": 200},
          "camera": {"height_above_ground_m": 2, "yaw_deg": 40, "pitch_deg": 30, "fov_deg": 70, "width": 32, "height": 18},
          "clouds": {"seed": 7, "layers": [{"kind": "cumulus", "bottom_m": 1500, "top_m": 2700, "coverage": 0.5, "extinction_scale": 0.3},
                                           {"kind": "stratocumulus", "bottom_m": 4000, "top_m": 4800, "coverage": 0.6, "extinction_scale": 0.3}]}})",
      "<deck test>");
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = AerialPerspective::Off;
  const RenderResult gpu = test::cloudRenderer().render(scene, o);
  const CloudSettings settings = CloudSettings::fromScene(scene);
  const SceneView& view = gpu.view;
  const CloudMedium medium = cloudMediumFor(context(), scene, settings, o, view);
  CloudReferenceSettings rs;
  rs.samplesPerPixel = 64;
  CloudPathTracer tracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{}, rs);
  const CloudReferenceImage ref = renderCloudReference(tracer, glm::dvec3(0.0, 0.0, view.cameraRadius), view.camera, 0);
  const CloudReferenceError e = compareWithCloudReference(gpu.clouds, ref);
  double se2 = 0.0;
  for (size_t i = 0; i < ref.image.pixelCount(); ++i)
    if (ref.image.pixels[4 * i + 3] < 0.95) se2 += ref.luminanceStandardError[i] * ref.luminanceStandardError[i];
  const double meanSe = e.pixels > 0 ? std::sqrt(se2) / e.pixels / e.meanReference : 0.0;
  std::printf("under a deck, %d cloud pixels: rel RMSE %.3f (noise %.3f, corrected %.3f), bias %+.3f (reference SE of the mean %.3f; %.1f s)\n",
              e.pixels, e.relRmse, e.noiseFloor, e.noiseCorrected, e.meanBias, meanSe, ref.seconds);
  ASSERT_GT(e.pixels, 100);
  EXPECT_LT(std::abs(e.meanBias), 0.08 + 2.0 * meanSe);
}

// The approximate Mie phase (HG + Draine, 20 um droplets) on both sides: the fast path's one octave
// against the path tracer's first order, the same bounds as the dual-HG noon case.
TEST_F(CloudReference, SingleScatteringWithTheApproximateMiePhase) {
  const Scene cumulus = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
                                          "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500", "/clouds/lighting/ms_octaves=1",
                                          "/clouds/lighting/phase=approximate_mie"});
  const SingleScatteringResult noon = singleScattering(context(), cumulus, 64);
  ASSERT_GT(noon.march.pixels, 20);
  EXPECT_LT(std::abs(noon.march.meanBias), 0.03 + 3.0 * noon.meanStandardError);
  EXPECT_LT(noon.march.noiseCorrected, 0.08);
}

// δ-HG scaling of a narrow forward lobe (CloudReferenceSettings::deltaLobeMinG), checked where the
// unscaled path tracer still converges: a first lobe g = 0.95 (peak 62 sr^-1; weight 0.6, second lobe
// HG(-0.3)). Mean cloud-pixel luminance, outside the aureole cone (CloudPathTracer::aureoleCosine), of
// the δ-scaled reference (128 paths) against the unscaled one (512).
struct DeltaScaledComparison {
  double scaledMean = 0.0, fullMean = 0.0, standardError = 0.0;  // standard error of scaled/full - 1
  double perPathNoiseScaled = 0.0, perPathNoiseFull = 0.0;       // noise floor x sqrt(paths)
  int pixels = 0, aureolePixels = 0;
  double ratio() const { return scaledMean / fullMean - 1.0; }
};

// One comparison per entry of exactSingleScattering (CloudReferenceSettings::exactSingleScattering of the
// scaled reference), all against the same unscaled reference.
std::vector<DeltaScaledComparison> compareDeltaScaled(gpu::Context& context, const Scene& scene,
                                                      const std::vector<bool>& exactSingleScattering) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.ambient = false;
  o.clouds.aerialPerspective = AerialPerspective::Off;
  const RenderResult gpu = test::cloudRenderer().render(scene, o);
  CloudSettings settings = CloudSettings::fromScene(scene);
  settings.lighting.gForward = 0.95;
  settings.lighting.backWeight = 0.4;
  const SceneView& view = gpu.view;
  const CloudMedium medium = cloudMediumFor(context, scene, settings, o, view);
  auto reference = [&](double deltaLobeMinG, int spp, bool exact) {
    CloudReferenceSettings rs;
    rs.samplesPerPixel = spp;
    rs.deltaLobeMinG = deltaLobeMinG;
    rs.exactSingleScattering = exact;
    CloudPathTracer tracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{}, rs);
    EXPECT_NEAR(tracer.deltaLobeFraction(), deltaLobeMinG <= 0.95 ? 0.6 * 0.95 * 0.95 : 0.0, 1e-12);
    return renderCloudReference(tracer, glm::dvec3(0.0, 0.0, view.cameraRadius), view.camera, 0);
  };
  constexpr int kScaledPaths = 128, kFullPaths = 512;
  const CloudReferenceImage full = reference(2.0, kFullPaths, true);
  EXPECT_EQ(std::count(full.inAureole.begin(), full.inAureole.end(), 1), 0);  // unscaled: trusted everywhere
  const double perPathNoiseFull = compareWithCloudReference(full.image, full).noiseFloor * std::sqrt(double(kFullPaths));
  std::vector<DeltaScaledComparison> out;
  for (const bool exact : exactSingleScattering) {
    const CloudReferenceImage scaled = reference(0.95, kScaledPaths, exact);
    DeltaScaledComparison c;
    double se2 = 0.0;
    for (size_t i = 0; i < full.image.pixelCount(); ++i) {
      if (full.image.pixels[4 * i + 3] >= 0.95f) continue;  // cloud pixels (the same true alpha in both)
      if (scaled.inAureole[i]) {
        ++c.aureolePixels;
        continue;
      }
      ++c.pixels;
      c.scaledMean += scaled.luminance[i];
      c.fullMean += full.luminance[i];
      se2 += full.luminanceStandardError[i] * full.luminanceStandardError[i] +
             scaled.luminanceStandardError[i] * scaled.luminanceStandardError[i];
    }
    if (c.pixels > 0) {
      c.standardError = std::sqrt(se2) / c.fullMean;
      c.scaledMean /= c.pixels;
      c.fullMean /= c.pixels;
    }
    c.perPathNoiseScaled = compareWithCloudReference(scaled.image, scaled).noiseFloor * std::sqrt(double(kScaledPaths));
    c.perPathNoiseFull = perPathNoiseFull;
    std::printf("g = 0.95 lobe, all orders, %d cloud pixels (%d in the aureole cone left out), exact first order %s: "
                "delta-scaled mean %.2f, full %.2f, ratio - 1 = %+.4f (SE %.4f); noise per path %.2f vs %.2f\n",
                c.pixels, c.aureolePixels, exact ? "on" : "off", c.scaledMean, c.fullMean, c.ratio(), c.standardError,
                c.perPathNoiseScaled, c.perPathNoiseFull);
    out.push_back(c);
  }
  return out;
}

// Away from the peak (up 60 deg, the sun 40 deg from the zenith behind the camera): the scaled reference
// agrees in the mean with the unscaled one within 3 % plus 3 standard errors and is quieter per path.
// (The approximate Mie's 20 um peak, g = 0.9946, is where the unscaled estimator fails: docs/clouds.md
// "Reference".)
TEST_F(CloudReference, DeltaScaledReferenceAgreesWithTheFullOne) {
  const Scene scene = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
                                        "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500"});
  const DeltaScaledComparison c = compareDeltaScaled(context(), scene, {true}).at(0);
  ASSERT_GT(c.pixels, 20);
  EXPECT_EQ(c.aureolePixels, 0);
  EXPECT_LT(std::abs(c.ratio()), 0.03 + 3.0 * c.standardError);
  EXPECT_LT(c.perPathNoiseScaled, c.perPathNoiseFull);
}

// Looking into the sun through the clouds (fov 90 deg centred on it): the δ sends the peak's light
// straight on, so the scaled transport alone loses the light forward-scattered towards the camera far
// outside the cone too (-37 % outside 15 deg when measured); with TMS (the exact phase at the view
// ray's first event) it agrees outside the cone.
TEST_F(CloudReference, DeltaScaledReferenceKeepsTheForwardPeak) {
  const Scene scene = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
                                        "/camera/yaw_deg=180", "/camera/pitch_deg=50", "/camera/fov_deg=90",
                                        "/clouds/layers/0/top_m=2500"});
  const std::vector<DeltaScaledComparison> c = compareDeltaScaled(context(), scene, {true, false});
  const DeltaScaledComparison& exact = c.at(0);
  const DeltaScaledComparison& scaledOnly = c.at(1);
  ASSERT_GT(exact.pixels, 20);
  EXPECT_GT(exact.aureolePixels, 10);
  EXPECT_LT(std::abs(exact.ratio()), 0.03 + 3.0 * exact.standardError);
  EXPECT_LT(scaledOnly.ratio(), -0.2);
}

}  // namespace
}  // namespace firmament
