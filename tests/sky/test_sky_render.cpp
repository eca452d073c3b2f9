// The clear-sky fast path on the GPU (lavapipe in CI) over the stability cases of the atmosphere
// issue: every pixel finite and non-negative for any camera altitude and sun angle, and zero
// validation messages (GpuTest).
#include <gtest/gtest.h>

#include <cmath>

#include "core/color.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class SkyRenderTest : public test::GpuTest {
 protected:
  static SkyRenderer& renderer() {
    static SkyRenderer r(context());
    return r;
  }
  // Renders a small image of the default scene with the given overrides.
  static RenderResult render(std::vector<std::string> overrides, int width = 48, int height = 32) {
    overrides.push_back("/camera/width=" + std::to_string(width));
    overrides.push_back("/camera/height=" + std::to_string(height));
    Scene scene = Scene::parse("{}", "<test>", overrides);
    return renderer().render(scene);
  }
  static void expectFiniteNonNegative(const Image& image, const std::string& what) {
    size_t bad = 0;
    for (float v : image.pixels) bad += !(std::isfinite(v) && v >= 0.0f);
    EXPECT_EQ(bad, 0u) << what;
  }
  static double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.pixelCount(); ++i) sum += luminanceRec709(image.pixels.data() + i * 4);
    return sum / double(image.pixelCount());
  }
};

TEST_F(SkyRenderTest, DefaultSceneIsBrightDaylight) {
  RenderResult r = render({"/sun/zenith_deg=30"});
  expectFiniteNonNegative(r.image, "noon");
  // A clear daytime sky is thousands of cd/m² (about 2000-10000 away from the sun).
  double mean = meanLuminance(r.image);
  EXPECT_GT(mean, 1000.0);
  EXPECT_LT(mean, 20000.0);
  EXPECT_FALSE(r.timings.empty());
}

TEST_F(SkyRenderTest, EverySunZenithIsFiniteAndDarkensAtNight) {
  double previous = 1e30;
  for (int zenith = 0; zenith <= 180; zenith += 1) {
    RenderResult r = render(
        {"/sun/zenith_deg=" + std::to_string(zenith), "/sun/azimuth_deg=90", "/camera/projection=equirectangular"}, 16,
        8);
    expectFiniteNonNegative(r.image, "sun zenith " + std::to_string(zenith));
    double mean = meanLuminance(r.image);
    // The whole-sphere mean falls as the sun sinks (a small tolerance for the sun at the horizon).
    EXPECT_LE(mean, previous * 1.02 + 1e-6) << "sun zenith " << zenith;
    previous = mean;
  }
  EXPECT_LT(previous, 1e-3);  // sun 90 degrees below the horizon: no single or multiple scattering
}

TEST_F(SkyRenderTest, AnyCameraAltitudeIsFinite) {
  for (const char* height : {"-100", "0", "1", "10000", "100000", "1000000", "100000000"}) {
    RenderResult r = render({std::string("/camera/height_above_ground_m=") + height, "/camera/pitch_deg=-30",
                             "/camera/projection=equirectangular", "/sun/zenith_deg=60"},
                            32, 16);
    expectFiniteNonNegative(r.image, std::string("camera height ") + height);
  }
}

TEST_F(SkyRenderTest, TablesAreReusedWhileTheAtmosphereIsUnchanged) {
  render({"/atmosphere/ground_albedo=0.3"});
  RenderResult again = render({"/atmosphere/ground_albedo=0.3", "/camera/yaw_deg=10"});
  EXPECT_TRUE(again.tablesReused);
  RenderResult changed = render({"/atmosphere/ground_albedo=0.2"});
  EXPECT_FALSE(changed.tablesReused);
}

// In a sequence the sky-view table is kept while the camera only turns (it is in the sun's frame), and
// the frame is bit for bit what a renderer that computes it anew gives; a new sun angle or altitude
// recomputes it, and a still always does.
TEST_F(SkyRenderTest, SkyViewTableIsKeptWhileTheCameraOnlyTurns) {
  auto frame = [](SkyRenderer& renderer, const std::vector<std::string>& extra, bool continueSequence) {
    std::vector<std::string> overrides = {"/atmosphere/ground_albedo=0.23", "/sun/zenith_deg=50", "/camera/width=48",
                                          "/camera/height=32"};
    overrides.insert(overrides.end(), extra.begin(), extra.end());  // the later override of a field wins
    SkyRenderOptions options;
    options.continueSequence = continueSequence;
    return renderer.render(Scene::parse("{}", "<test>", overrides), options);
  };
  auto hasSkyViewPass = [](const RenderResult& r) {
    for (const auto& t : r.timings)
      if (t.label == "sky/sky_view_lut") return true;
    return false;
  };
  SkyRenderer& sequence = renderer();
  const RenderResult first = frame(sequence, {"/camera/yaw_deg=0"}, false);
  EXPECT_FALSE(first.skyViewReused);
  EXPECT_TRUE(hasSkyViewPass(first));
  const RenderResult turned = frame(sequence, {"/camera/yaw_deg=40", "/camera/pitch_deg=20"}, true);
  EXPECT_TRUE(turned.skyViewReused);
  EXPECT_FALSE(hasSkyViewPass(turned));
  SkyRenderer fresh(context());
  const RenderResult computed = frame(fresh, {"/camera/yaw_deg=40", "/camera/pitch_deg=20"}, true);
  EXPECT_FALSE(computed.skyViewReused);
  ASSERT_EQ(computed.image.pixels.size(), turned.image.pixels.size());
  EXPECT_EQ(computed.image.pixels, turned.image.pixels);
  // Each change follows a frame that differs from it in that input alone.
  EXPECT_FALSE(frame(sequence, {"/camera/yaw_deg=40"}, false).skyViewReused);  // a still
  EXPECT_FALSE(frame(sequence, {"/sun/zenith_deg=51"}, true).skyViewReused);
  frame(sequence, {}, false);
  EXPECT_FALSE(frame(sequence, {"/camera/height_above_ground_m=100"}, true).skyViewReused);
}

TEST_F(SkyRenderTest, EmptyAtmosphereShowsOnlySunAndGround) {
  RenderResult r = render({"/atmosphere/rayleigh_scattering_um4=0", "/atmosphere/mie/angstrom_beta=0",
                           "/atmosphere/ozone/column_dobson=0", "/sun/zenith_deg=30", "/camera/pitch_deg=60"});
  expectFiniteNonNegative(r.image, "empty atmosphere");
  // Looking up, away from the sun, into an empty atmosphere: black.
  const float* p = r.image.at(r.image.width / 2, 0);
  EXPECT_EQ(p[0] + p[1] + p[2], 0.0f);
}

}  // namespace
}  // namespace firmament

namespace firmament {
namespace {

class SkyTableCacheTest : public test::GpuTest {};

// A second renderer (nothing in memory) reads the tables from the disk cache and renders the same
// bits as the renderer that computed them.
TEST_F(SkyTableCacheTest, DiskCacheGivesIdenticalPixels) {
  Scene scene =
      Scene::parse("{}", "<test>", {"/camera/width=24", "/camera/height=16", "/atmosphere/ground_albedo=0.37"});
  SkyRenderer first(context());
  RenderResult a = first.render(scene);
  EXPECT_EQ(a.tablesSource, "computed");
  SkyRenderer second(context());
  RenderResult b = second.render(scene);
  EXPECT_EQ(b.tablesSource, "disk cache");
  EXPECT_EQ(a.image.pixels, b.image.pixels);
}

}  // namespace
}  // namespace firmament

namespace firmament {
namespace {

class SkyStabilityTest : public test::GpuTest {
 protected:
  static RenderResult render(SkyRenderer& renderer, std::vector<std::string> overrides, const SkyRenderOptions& options,
                             int width, int height) {
    overrides.push_back("/camera/width=" + std::to_string(width));
    overrides.push_back("/camera/height=" + std::to_string(height));
    return renderer.render(Scene::parse("{}", "<test>", overrides), options);
  }
  static double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.pixelCount(); ++i) sum += luminanceRec709(image.pixels.data() + i * 4);
    return sum / double(image.pixelCount());
  }
  static bool finiteNonNegative(const Image& image) {
    for (float v : image.pixels)
      if (!(std::isfinite(v) && v >= 0.0f)) return false;
    return true;
  }
};

// Haze 100 times thicker than Bruneton's Earth (an optically thick aerosol layer) stays finite, and
// its transmittance table stays in [0, 1].
TEST_F(SkyStabilityTest, ThickHazeAndTransmittanceInUnitRange) {
  SkyRenderer renderer(context());
  for (const char* beta : {"0.5328", "0.005328"}) {
    RenderResult r = render(renderer,
                            {std::string("/atmosphere/mie/angstrom_beta=") + beta, "/sun/zenith_deg=70",
                             "/camera/projection=equirectangular"},
                            {}, 32, 16);
    EXPECT_TRUE(finiteNonNegative(r.image)) << "beta " << beta;
  }
  // The tables of the last render: transmittance of every texel in [0, 1].
  AtmosphereLuts luts(context());
  AtmosphereSettings thick;
  thick.mieAngstromBeta = 0.5328;
  luts.update(thick, {});
  for (float v : luts.transmittance().downloadFloats()) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
}

// Rays within 1e-5 rad of the horizon, above and below it, from a camera 2 m above the ground.
TEST_F(SkyStabilityTest, GrazingRaysAreFinite) {
  SkyRenderer renderer(context());
  const double radius = 6360e3;
  const double dip = std::acos(radius / (radius + 2.0)) * 180.0 / 3.14159265358979323846;
  for (double offset : {-1e-5, -1e-6, 0.0, 1e-6, 1e-5}) {
    double pitch = -dip + offset * 180.0 / 3.14159265358979323846;
    for (SkyMethod method : {SkyMethod::SkyViewLut, SkyMethod::PerPixel}) {
      SkyRenderOptions options;
      options.method = method;
      RenderResult r = render(renderer,
                              {"/location/height_m=0", "/camera/pitch_deg=" + std::to_string(pitch),
                               "/camera/fov_deg=0.001", "/sun/zenith_deg=89"},
                              options, 3, 3);
      EXPECT_TRUE(finiteNonNegative(r.image)) << "offset " << offset;
    }
  }
}

// The per-pixel march converges as its steps grow: the error against 512 steps shrinks at every
// doubling.
TEST_F(SkyStabilityTest, RadianceConvergesAsStepsGrow) {
  SkyRenderer renderer(context());
  SkyRenderOptions options;
  options.method = SkyMethod::PerPixel;
  options.viewSteps = 512;
  std::vector<std::string> view = {"/sun/zenith_deg=60", "/camera/pitch_deg=5"};
  double reference = meanLuminance(render(renderer, view, options, 16, 9).image);
  double previous = 1e30;
  for (int steps : {4, 8, 16, 32, 64, 128}) {
    options.viewSteps = steps;
    double error = std::abs(meanLuminance(render(renderer, view, options, 16, 9).image) - reference);
    EXPECT_LT(error, previous) << steps << " steps";
    previous = error;
  }
  EXPECT_LT(previous / reference, 2e-3);  // 128 steps: within 0.2 % of 512
}

}  // namespace
}  // namespace firmament
