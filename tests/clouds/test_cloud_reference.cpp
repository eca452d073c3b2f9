// The GPU march against the CPU path tracer on one small cumulus scene (same density from the same
// textures, same phase function, same sun through the atmosphere). Ambient light and aerial
// perspective are off in both, so the comparison isolates the cloud transport of sunlight: the
// march's octave multiple-scattering approximation against all orders; and the single scattering
// alone against the path tracer's first order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

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
  return CloudMedium(sharedCloudLayers(settings, ground), noise.downloadShape(), noise.downloadDetail(),
                     noise.downloadCurl(), cloudWeatherMapForScene(scene), ground);
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

// The reference's standard error of its mean over the cloud pixels that `e` compared, relative to that mean.
double relativeStandardErrorOfMean(const CloudReferenceImage& ref, const CloudReferenceError& e) {
  double se2 = 0.0;
  for (size_t i = 0; i < ref.image.pixelCount(); ++i)
    if (ref.image.pixels[4 * i + 3] < 0.95) se2 += ref.luminanceStandardError[i] * ref.luminanceStandardError[i];
  return e.pixels > 0 ? std::sqrt(se2) / e.pixels / e.meanReference : 0.0;
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
  std::printf(
      "cloud pixels %d: rel RMSE of luminance %.3f (reference noise %.3f, noise-corrected %.3f); mean GPU "
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

// The same thin cumulus under a sun 80 deg from the zenith, to the side, looked at 20 deg up, all orders,
// the shipped model: the octaves, fitted under higher suns, give nearly twice the path tracer's light
// (measured +92 %; looking up 60 deg, 2.9x) with the single scattering right. Cumulus's
// low-sun scale (cloudOctaveLowSunScale, mu_0 fitted on the calibration's low-sun scenes, not on this
// one) must bring it within the bounds of the noon case above (measured -2.5 %; -10 % without the
// reflected light's low-sun depth scale; the reference's SE of the mean 3 %), while the model without it stays far too
// bright (the check can fail).
TEST_F(CloudReference, LowSunCumulusAgainstPathTracer) {
  const Scene scene = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24",
                                        "/camera/height=14", "/camera/pitch_deg=20", "/clouds/layers/0/top_m=2500",
                                        "/sun/zenith_deg=80", "/sun/azimuth_deg=90"});
  SkyRenderOptions o = fineMarchOptions();
  const RenderResult shipped = test::cloudRenderer().render(scene, o);
  o.clouds.reflectedLowSunDepth = false;
  const RenderResult withoutDepthScale = test::cloudRenderer().render(scene, o);
  o.clouds.octaveLowSunMu = 0.0;
  const RenderResult off = test::cloudRenderer().render(scene, o);
  const CloudSettings settings = CloudSettings::fromScene(scene);
  ASSERT_GT(settings.layers[0].msLowSunMu, 0.174);  // the scale is on at this sun (mu_s 0.174)
  const SceneView& view = shipped.view;
  const CloudMedium medium = cloudMediumFor(context(), scene, settings, o, view);
  CloudReferenceSettings rs;
  rs.samplesPerPixel = 64;
  const CloudPathTracer tracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{}, rs);
  const CloudReferenceImage ref = renderCloudReference(tracer, glm::dvec3(0.0, 0.0, view.cameraRadius), view.camera, 0);
  const CloudReferenceError e = compareWithCloudReference(shipped.clouds, ref);
  const CloudReferenceError eOff = compareWithCloudReference(off.clouds, ref);
  const CloudReferenceError e27 = compareWithCloudReference(withoutDepthScale.clouds, ref);
  ASSERT_GT(e.pixels, 20);
  const double meanSe = relativeStandardErrorOfMean(ref, e);
  std::printf(
      "sun 80 deg, %d cloud pixels: the shipped model bias %+.3f (rel RMSE %.3f noise-corrected), with the reflected "
      "light's a_r whatever the sun %+.3f (%.3f), without the low-sun scale %+.3f (%.3f); reference SE of the mean "
      "%.3f\n",
      e.pixels, e.meanBias, e.noiseCorrected, e27.meanBias, e27.noiseCorrected, eOff.meanBias, eOff.noiseCorrected,
      meanSe);
  EXPECT_LT(e.meanBias, 0.25 + 3.0 * meanSe);
  EXPECT_GT(e.meanBias, -0.15 - 3.0 * meanSe);
  EXPECT_GT(eOff.meanBias, 0.8);
}

// The ambient (sky and ground light; docs/clouds.md "Lighting") against paths that see a constant sky
// and a Lambertian ground where they leave the shells: the light each side gains from them, summed over
// the cloud pixels. The fast path's sky irradiance comes from its tables at each sample, the path
// tracer's from the clear-sky reference at layer 0's mid-height. `variants` turn the ambient on in ways
// to compare (each one GPU render); the gains are per pixel.
struct AmbientGain {
  std::vector<double> gpu;  // per variant
  std::vector<CloudReferenceError>
      error;  // per variant: its image (sunlight and ambient) against the path tracer with both
  // Per variant: the per-pixel gain's relative RMSE, noise-corrected (the references' variance taken out).
  std::vector<double> gainRmse;
  double reference = 0.0, standardError = 0.0, gpuSunlight = 0.0, referenceSunlight = 0.0;
  // Of the mean gain, from its even and odd paths: both references trace the same paths, so it is far
  // below standardError, which takes their images' noise as independent.
  double gainStandardError = 0.0;
  int pixels = 0;
};

AmbientGain ambientGain(gpu::Context& context, const Scene& scene, SkyRenderOptions o, int samplesPerPixel,
                        const std::vector<std::function<void(SkyRenderOptions&)>>& variants) {
  o.clouds.ambient = false;
  const RenderResult sunOnly = test::cloudRenderer().render(scene, o);
  std::vector<RenderResult> on;
  for (const auto& apply : variants) {
    SkyRenderOptions v = o;
    v.clouds.ambient = true;
    apply(v);
    on.push_back(test::cloudRenderer().render(scene, v));
  }
  const CloudSettings settings = CloudSettings::fromScene(scene);
  const SceneView& view = sunOnly.view;
  const CloudMedium medium = cloudMediumFor(context, scene, settings, o, view);
  CloudReferenceSettings rs;
  rs.samplesPerPixel = samplesPerPixel;
  const double ground = view.cameraRadius - scene.number("/camera/height_above_ground_m");
  const double middle = 0.5 * (settings.layers[0].bottom_m + settings.layers[0].top_m);
  const CloudEnvironment environment =
      cloudEnvironmentFromReference(view.atmosphere, view.sunDirection, ground + middle);
  const CloudPathTracer sunTracer(medium, settings.lighting, view.atmosphere, view.sunDirection, CloudEnvironment{},
                                  rs);
  const CloudPathTracer skyTracer(medium, settings.lighting, view.atmosphere, view.sunDirection, environment, rs);
  const glm::dvec3 camera(0.0, 0.0, view.cameraRadius);
  const CloudReferenceImage refSun = renderCloudReference(sunTracer, camera, view.camera, 0);
  const CloudReferenceImage refSky = renderCloudReference(skyTracer, camera, view.camera, 0);

  AmbientGain g;
  g.gpu.assign(variants.size(), 0.0);
  double se2 = 0.0, reference2 = 0.0, gainVariance = 0.0;
  std::vector<double> squared(variants.size(), 0.0);
  for (size_t i = 0; i < refSun.image.pixelCount(); ++i) {
    if (refSun.image.pixels[4 * i + 3] > 0.95) continue;
    const double off = luminanceRec709(sunOnly.clouds.pixels.data() + 4 * i);
    const double referenceGain = refSky.luminance[i] - refSun.luminance[i];
    for (size_t v = 0; v < on.size(); ++v) {
      const double y = luminanceRec709(on[v].clouds.pixels.data() + 4 * i);
      EXPECT_TRUE(std::isfinite(y));
      EXPECT_GE(y, off * (1.0 - 1e-5));  // the ambient only adds light
      g.gpu[v] += y - off;
      squared[v] += (y - off - referenceGain) * (y - off - referenceGain);
    }
    g.gpuSunlight += off;
    g.reference += referenceGain;
    reference2 += referenceGain * referenceGain;
    g.referenceSunlight += refSun.luminance[i];
    se2 += refSky.luminanceStandardError[i] * refSky.luminanceStandardError[i] +
           refSun.luminanceStandardError[i] * refSun.luminanceStandardError[i];
    // Both references trace the same paths (same seed and streams; the environment only adds where a
    // path leaves), so the gain's own noise is far below the two images' noise: its variance from the
    // even and odd paths' gains, E[(g_even - g_odd)^2] / 4.
    const double halves = (refSky.luminanceEvenPaths[i] - refSun.luminanceEvenPaths[i]) -
                          (refSky.luminanceOddPaths[i] - refSun.luminanceOddPaths[i]);
    gainVariance += 0.25 * halves * halves;
    ++g.pixels;
  }
  g.gainStandardError = std::sqrt(gainVariance);
  for (double s2 : squared)
    g.gainRmse.push_back(reference2 > 0.0 ? std::sqrt(std::max(s2 - gainVariance, 0.0) / reference2) : 0.0);
  g.standardError = std::sqrt(se2);  // of the summed gain (the two references' noise is independent)
  if (g.pixels > 0) {
    for (double& v : g.gpu) v /= g.pixels;
    g.reference /= g.pixels;
    g.standardError /= g.pixels;
    g.gainStandardError /= g.pixels;
    g.gpuSunlight /= g.pixels;
    g.referenceSunlight /= g.pixels;
  }
  for (size_t v = 0; v < g.gpu.size(); ++v) {
    g.error.push_back(compareWithCloudReference(on[v].clouds, refSky));
    std::printf(
        "cloud pixels %d: variant %zu of the ambient adds %.1f cd/m^2 a pixel on the GPU, %.1f +- %.1f in the path "
        "tracer (+- %.1f over the same paths; ratio %.3f, per pixel %.3f); sunlight alone %.1f and %.1f; with it, rel "
        "RMSE %.3f noise-corrected, bias %+.3f\n",
        g.pixels, v, g.gpu[v], g.reference, g.standardError, g.gainStandardError, g.gpu[v] / g.reference, g.gainRmse[v],
        g.gpuSunlight, g.referenceSunlight, g.error[v].noiseCorrected, g.error[v].meanBias);
  }
  return g;
}

TEST_F(CloudReference, AmbientAgainstPathTracerWithSkyAndGround) {
  const AmbientGain g =
      ambientGain(context(), thinCumulusScene(), fineMarchOptions(), 48,
                  {[](SkyRenderOptions&) {}, [](SkyRenderOptions& v) { v.clouds.ambientFlow = 0.0; }});
  ASSERT_GT(g.pixels, 20);
  EXPECT_GT(g.reference, 10.0 * g.gainStandardError);  // the sky's light is resolved by the references
  // Measured 1651 against 1591 +- 8 a pixel (ratio 1.038, per-pixel error of the gain 0.047); the slab's
  // J alone (CloudMarchSettings::ambientFlow 0) 1802 (1.133, per pixel 0.134: its ground
  // light 1.44x the path tracer's, its sky 0.77x); the ambient by height 1377 (0.87).
  // Bounds: within 10 % + 3 SE, which J alone fails, and closer per pixel than J alone.
  EXPECT_LE(std::abs(g.gpu[0] - g.reference), 0.10 * g.reference + 3.0 * g.gainStandardError);
  EXPECT_LT(g.gainRmse[0], g.gainRmse[1]);
}

// A cumulus under a deck (by default the stratocumulus of ALayerUnderADeckKeepsTheDecksDiffuseLight below).
Scene cumulusUnderADeck(
    const std::string& deck = R"("kind": "stratocumulus", "bottom_m": 4000, "top_m": 4800, "coverage": 0.6)") {
  return Scene::parse(
      R"({"location": {"height_m": 300}, "sun": {"zenith_deg": 30, "azimuth_deg": 200},
          "camera": {"height_above_ground_m": 2, "yaw_deg": 40, "pitch_deg": 30, "fov_deg": 70, "width": 32, "height": 18},
          "clouds": {"seed": 7, "layers": [{"kind": "cumulus", "bottom_m": 1500, "top_m": 2700, "coverage": 0.5, "extinction_scale": 0.3},
                                           {)" +
          deck + R"(, "extinction_scale": 0.3}]}})",
      "<deck test>");
}

// The same cumulus under an unbroken stratus deck: the ambient's slab through both layers' columns
// (CloudMarchSettings::ambientThroughOtherLayers, column_map.glsl columnMapOtherLayersOpticalDepths)
// against each layer as its own slab, under which the cumulus sees the whole sky.
// Measured (128 paths): the ambient adds 2532 against the path tracer's 2610 +- 3 a pixel (0.970;
// its own slab 0.914), per-pixel relative error of the gain 0.051 (its own slab 0.096); the whole
// image 0.144 / -7.8 % (0.157 / -9.2 %). Without the slab's flow (ambientFlow 0) the same comparison was 1.010 against
// 0.970, per pixel 0.040 against 0.051. Bounds: the mean within 5 % + 3 SE, and the per-pixel error below its own
// slab's, which each layer alone fails.
TEST_F(CloudReference, AmbientUnderADeckAgainstPathTracer) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.aerialPerspective = AerialPerspective::Off;
  const AmbientGain g = ambientGain(
      context(), cumulusUnderADeck(R"("kind": "stratus", "bottom_m": 4000, "top_m": 4600, "coverage": 1.0)"), o, 128,
      {[](SkyRenderOptions&) {}, [](SkyRenderOptions& v) { v.clouds.ambientThroughOtherLayers = false; }});
  ASSERT_GT(g.pixels, 100);
  EXPECT_GT(g.reference, 10.0 * g.gainStandardError);
  EXPECT_LE(std::abs(g.gpu[0] - g.reference), 0.05 * g.reference + 3.0 * g.gainStandardError);
  EXPECT_LT(g.gainRmse[0], g.gainRmse[1]);
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
  r.meanStandardError = relativeStandardErrorOfMean(ref, r.march);
  std::printf(
      "single scattering, %d cloud pixels: rel RMSE %.3f (noise %.3f, corrected %.3f), mean %.1f vs %.1f "
      "(bias %+.3f, reference SE of the mean %.3f); milestone 1's fixed-length light march: bias %+.3f; own layer "
      "only: corrected %.3f, bias %+.3f\n",
      r.march.pixels, r.march.relRmse, r.march.noiseFloor, r.march.noiseCorrected, r.march.meanTest,
      r.march.meanReference, r.march.meanBias, r.meanStandardError, r.fixedLength.meanBias,
      r.ownLayerOnly.noiseCorrected, r.ownLayerOnly.meanBias);
  return r;
}

TEST_F(CloudReference, SingleScatteringAgreesWithFirstOrder) {
  const Scene cumulus =
      test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24", "/camera/height=14",
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
      {"/clouds/layers/0/extinction_scale=0.2", "/clouds/layers/1/extinction_scale=0.1", "/camera/width=24",
       "/camera/height=14", "/camera/pitch_deg=60", "/clouds/lighting/ms_octaves=1"},
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
// it, -21 % (the cumulus fit with a = 0.445). This scene (like the bench's, other seed and
// sun) measured -5.2 % with it and -14.1 % without (a scratch build; the reference's standard error of
// the mean 1.9 %). Bound: 8 % + 2 standard errors (11.8 %).
TEST_F(CloudReference, ALayerUnderADeckKeepsTheDecksDiffuseLight) {
  const Scene scene = cumulusUnderADeck();
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
  std::printf(
      "under a deck, %d cloud pixels: rel RMSE %.3f (noise %.3f, corrected %.3f), bias %+.3f (reference SE of the mean "
      "%.3f; %.1f s)\n",
      e.pixels, e.relRmse, e.noiseFloor, e.noiseCorrected, e.meanBias, meanSe, ref.seconds);
  ASSERT_GT(e.pixels, 100);
  EXPECT_LT(std::abs(e.meanBias), 0.08 + 2.0 * meanSe);
}

// The approximate Mie phase (HG + Draine, 20 um droplets) on both sides: the fast path's one octave
// against the path tracer's first order, the same bounds as the dual-HG noon case.
TEST_F(CloudReference, SingleScatteringWithTheApproximateMiePhase) {
  const Scene cumulus = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24",
                                          "/camera/height=14", "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500",
                                          "/clouds/lighting/ms_octaves=1", "/clouds/lighting/phase=approximate_mie"});
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
  const double perPathNoiseFull =
      compareWithCloudReference(full.image, full).noiseFloor * std::sqrt(double(kFullPaths));
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
    std::printf(
        "g = 0.95 lobe, all orders, %d cloud pixels (%d in the aureole cone left out), exact first order %s: "
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
  const Scene scene = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24",
                                        "/camera/height=14", "/camera/pitch_deg=60", "/clouds/layers/0/top_m=2500"});
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
  const Scene scene = test::cloudScene({"/clouds/layers/0/extinction_scale=0.2", "/camera/width=24",
                                        "/camera/height=14", "/camera/yaw_deg=180", "/camera/pitch_deg=50",
                                        "/camera/fov_deg=90", "/clouds/layers/0/top_m=2500"});
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
