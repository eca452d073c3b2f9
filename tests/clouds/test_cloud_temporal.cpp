// Temporal reprojection of the clouds (docs/clouds.md "Temporal reprojection"): frames that continue a
// sequence march 1 in N pixels and reproject the rest (clouds/temporal_resolve.comp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "astro/time.h"
#include "common/camera.glsl"
#include "core/error.h"
#include "core/image_metrics.h"
#include "sky/render_plan.h"
#include "tests/clouds/cloud_test_support.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

shared::CameraParameters camera(int projection, double fovDeg, int width, int height) {
  shared::CameraParameters c{};
  shared::cameraBasis(0.4, 0.3, 0.1, c.forward, c.right, c.up);
  c.fov = fovDeg * 3.14159265358979323846 / 180.0;
  c.yaw = 0.4;
  c.projection = projection;
  c.width = width;
  c.height = height;
  return c;
}

// cameraPixelOfDirection inverts cameraRayDirection for every projection, to 1e-6 pixel.
TEST(CameraInverse, RoundTripsEveryProjection) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& c :
       {camera(shared::kProjectionPerspective, 75.0, 640, 360), camera(shared::kProjectionFisheye, 200.0, 512, 512),
        camera(shared::kProjectionEquirectangular, 360.0, 512, 256)}) {
    for (int i = 0; i < 2000; ++i) {
      const glm::dvec2 pixel(u(rng) * c.width, (0.002 + 0.996 * u(rng)) * c.height);
      bool valid = false;
      const glm::dvec3 dir = shared::cameraRayDirection(c, pixel, valid);
      if (!valid) continue;  // outside a fisheye's circle
      bool back = false;
      const glm::dvec2 again = shared::cameraPixelOfDirection(c, dir, back);
      ASSERT_TRUE(back) << c.projection << " " << pixel.x << " " << pixel.y;
      ASSERT_LT(glm::length(again - pixel), 1e-6) << c.projection << " " << pixel.x << " " << pixel.y;
    }
  }
  // Behind a perspective camera no pixel looks that way.
  const auto p = camera(shared::kProjectionPerspective, 75.0, 640, 360);
  bool valid = true;
  shared::cameraPixelOfDirection(p, -p.forward, valid);
  EXPECT_FALSE(valid);
}

TEST(CloudTemporalPlan, ResolveListedOnlyWithTemporalUpdate) {
  EXPECT_TRUE(planRender(test::cloudScene()).has("clouds/temporal_resolve"));  // 1/16 by default
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/temporal_update=1"})).has("clouds/temporal_resolve"));
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/resolution_divisor=2"})).has("clouds/temporal_resolve"));
  EXPECT_TRUE(planRender(test::cloudScene({"/clouds/temporal_update=4"})).has("clouds/temporal_resolve"));
  PlanOptions off;
  off.cloudTemporalUpdate = 1;
  EXPECT_FALSE(planRender(test::cloudScene({"/clouds/temporal_update=4"}), off).has("clouds/temporal_resolve"));
  EXPECT_FALSE(planRender(Scene::parse("{}", "<t>")).has("clouds/temporal_resolve"));
}

class CloudTemporal : public test::GpuTest {};

SkyRenderOptions temporal(int update, bool continueSequence, bool clamp = true) {
  SkyRenderOptions o = test::smallCloudOptions();
  o.clouds.temporalUpdate = update;
  o.clouds.temporalClamp = clamp;
  o.continueSequence = continueSequence;
  return o;
}

// A 160x90 view of the test cumulus, frame i of a sequence turning by yawStep per frame with the wind
// moving the field by windStep metres per frame.
Scene frameScene(int i, double yawStepDeg, double windStep_m) {
  return test::cloudScene(
      {"/camera/width=160", "/camera/height=90", "/camera/yaw_deg=" + std::to_string(yawStepDeg * i),
       "/clouds/wind_m_s=" + std::to_string(windStep_m), "/clouds/time_s=" + std::to_string(double(i))});
}

struct SequenceError {
  double relRmse = 0.0, relBias = 0.0;  // the last frame against a still of its view
  double samplesRatio = 0.0;            // view samples per pixel of the reprojected frames / the still's
};

SequenceError runSequence(int update, int frames, double yawStepDeg, double windStep_m, bool clamp = true) {
  SkyRenderer& renderer = test::cloudRenderer();
  double samples = 0.0;
  RenderResult last;
  for (int i = 0; i < frames; ++i) {
    last = renderer.render(frameScene(i, yawStepDeg, windStep_m), temporal(update, i > 0, clamp));
    EXPECT_EQ(last.cloudsReprojected, i > 0) << i;
    if (i > 0) samples += last.cloudSamples.viewPerPixel;
    for (float v : last.image.pixels) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
  }
  const RenderResult still = renderer.render(frameScene(frames - 1, yawStepDeg, windStep_m), temporal(update, false));
  EXPECT_FALSE(still.cloudsReprojected);
  for (size_t i = 0; i < last.clouds.pixelCount(); ++i) {
    const float t = last.clouds.pixels[4 * i + 3];
    EXPECT_TRUE(t >= 0.0f && t <= 1.0f) << i;
  }
  const ImageMetrics m = compareImages(last.image, still.image);
  SequenceError e{m.luminance.relativeRmse, m.luminance.relativeMeanBias,
                  samples / double(frames - 1) / still.cloudSamples.viewPerPixel};
  std::printf(
      "1/%d, %d frames, %.2f deg and %.0f m per frame%s: rel RMSE %.3f %%, bias %+.3f %%, samples %.3f of a still's\n",
      update, frames, yawStepDeg, windStep_m, clamp ? "" : " (no clamp)", 100.0 * e.relRmse, 100.0 * e.relBias,
      e.samplesRatio);
  return e;
}

// A still camera: after N frames every pixel was marched once, so the frame is a full march (other
// blue-noise offsets: the two differ by the jitter's noise only).
TEST_F(CloudTemporal, StillCameraConvergesToTheFullMarch) {
  for (int update : {4, 16}) {
    const SequenceError e = runSequence(update, update + 1, 0.0, 0.0);
    EXPECT_LT(e.relRmse, 0.01) << update;
    EXPECT_LT(std::abs(e.relBias), 0.002) << update;
    EXPECT_LT(e.samplesRatio, 1.5 / update) << update;
  }
  runSequence(16, 17, 0.0, 0.0, false);
}

// A turning camera and a moving field at 30 frames per second (7.5 deg/s, wind 20 m/s), and a harsher
// sequence (1 s per frame: 20 m of wind per frame): the reprojected frame stays close to a still of its view.
TEST_F(CloudTemporal, MovingCameraStaysCloseToTheFullMarch) {
  for (int update : {4, 16}) {
    const SequenceError e = runSequence(update, 2 * update + 1, 0.25, 20.0 / 30.0);
    EXPECT_LT(e.relRmse, 0.01) << update;
    EXPECT_LT(std::abs(e.relBias), 0.003) << update;
    EXPECT_LT(e.samplesRatio, 1.5 / update) << update;
    const SequenceError harsh = runSequence(update, 2 * update + 1, 0.25, 20.0);
    EXPECT_LT(harsh.relRmse, 0.02) << update;
    EXPECT_LT(std::abs(harsh.relBias), 0.003) << update;
  }
}

// The clamp's purpose: history that no longer belongs. Between frames 16 and 17 the sun drops from
// 40 to 60 degrees from the zenith (a time-lapse): the clamped frame is closer to a still than the
// unclamped one.
TEST_F(CloudTemporal, ClampRejectsHistoryThatNoLongerBelongs) {
  SkyRenderer& renderer = test::cloudRenderer();
  double error[2] = {0.0, 0.0};
  for (bool clamp : {false, true}) {
    for (int i = 0; i < 17; ++i) renderer.render(frameScene(i, 0.0, 0.0), temporal(16, i > 0, clamp));
    const Scene lower =
        test::cloudScene({"/camera/width=160", "/camera/height=90", "/sun/zenith_deg=60", "/clouds/time_s=17"});
    const RenderResult r = renderer.render(lower, temporal(16, true, clamp));
    EXPECT_TRUE(r.cloudsReprojected);
    const RenderResult still = renderer.render(lower, temporal(16, false));
    error[clamp] = compareImages(r.image, still.image).luminance.relativeRmse;
  }
  std::printf("sun 40 -> 60 deg: rel RMSE %.2f %% without the clamp, %.2f %% with it\n", 100.0 * error[0],
              100.0 * error[1]);
  EXPECT_LT(error[1], 0.5 * error[0]);
}

// Fisheye and equirectangular views (the inverse mappings, the fisheye's circle, the equirectangular
// seam). Both are mostly horizon, where the march's own blue-noise noise is large: a still sequence
// (17 frames, every pixel marched once with other jitter) already differs from a still by 6.8 % and
// 8.8 % (measured). Turning 0.5 deg per frame must stay finite and add at most that much again
// (measured 11.7 % and 9.3 %: the horizon's fine detail, compressed into the fisheye's rim, blurs as
// the history is resampled; a Catmull-Rom read took 10.5 % to 9.2 % before the per-thickness light march).
// The bias the turning adds is bounded by the still sequence's own plus half a point: the reflected light
// moved the still sequences' floor to 10.5 % and 12.7 %, bias -1.0 % and -1.4 % (without it
// 7.5 % and 9.4 %, -0.65 % and -1.0 %), and the turning ones to +0.16 % and -1.2 %.
TEST_F(CloudTemporal, OtherProjectionsStayNearTheirNoiseFloor) {
  SkyRenderer& renderer = test::cloudRenderer();
  for (const char* projection : {"fisheye", "equirectangular"}) {
    const bool fisheye = std::string(projection) == "fisheye";
    auto scene = [&](int i, double yawStep) {
      return test::cloudScene(
          {std::string("/camera/projection=") + projection, fisheye ? "/camera/width=96" : "/camera/width=128",
           fisheye ? "/camera/height=96" : "/camera/height=64", fisheye ? "/camera/fov_deg=180" : "/camera/fov_deg=360",
           fisheye ? "/camera/pitch_deg=90" : "/camera/pitch_deg=0", "/camera/yaw_deg=" + std::to_string(yawStep * i),
           "/clouds/wind_m_s=20", "/clouds/time_s=" + std::to_string(i / 30.0)});
    };
    double error[2] = {0.0, 0.0}, bias[2] = {0.0, 0.0};
    for (int moving = 0; moving < 2; ++moving) {
      const double yawStep = moving ? 0.5 : 0.0;
      RenderResult last;
      for (int i = 0; i < 17; ++i) {
        last = renderer.render(scene(i, yawStep), temporal(16, i > 0));
        EXPECT_EQ(last.cloudsReprojected, i > 0) << projection << " " << i;
        for (float v : last.image.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << projection;
      }
      const RenderResult still = renderer.render(scene(16, yawStep), temporal(16, false));
      const ImageMetrics m = compareImages(last.image, still.image);
      error[moving] = m.luminance.relativeRmse;
      bias[moving] = m.luminance.relativeMeanBias;
    }
    std::printf("%s, 1/16: still sequence %.2f %% (bias %+.2f %%), turning 0.5 deg per frame %.2f %% (bias %+.2f %%)\n",
                projection, 100.0 * error[0], 100.0 * bias[0], 100.0 * error[1], 100.0 * bias[1]);
    EXPECT_LT(error[1], 2.0 * error[0] + 0.01) << projection;
    EXPECT_LT(std::abs(bias[1]), std::abs(bias[0]) + 0.005) << projection;
    EXPECT_LT(std::abs(bias[1]), 0.02) << projection;
  }
}

// Stills, changed settings and a camera inside a layer march every pixel.
TEST_F(CloudTemporal, FallsBackToAFullMarch) {
  SkyRenderer& renderer = test::cloudRenderer();
  renderer.render(frameScene(0, 0.0, 0.0), temporal(16, false));
  EXPECT_FALSE(renderer.render(frameScene(1, 0.0, 0.0), temporal(16, false)).cloudsReprojected);  // a still
  EXPECT_TRUE(renderer.render(frameScene(2, 0.0, 0.0), temporal(16, true)).cloudsReprojected);
  // Other coverage: the history is another scene's.
  const Scene denser = test::cloudScene({"/camera/width=160", "/camera/height=90", "/clouds/layers/0/coverage=0.9"});
  EXPECT_FALSE(renderer.render(denser, temporal(16, true)).cloudsReprojected);
  EXPECT_TRUE(renderer.render(denser, temporal(16, true)).cloudsReprojected);
  // Flying through the layer (1500-4000 m above the ground): every frame marched.
  const Scene inside =
      test::cloudScene({"/camera/width=160", "/camera/height=90", "/camera/height_above_ground_m=2500"});
  renderer.render(inside, temporal(16, false));
  EXPECT_FALSE(renderer.render(inside, temporal(16, true)).cloudsReprojected);
  // temporal_update 1: never.
  renderer.render(frameScene(0, 0.0, 0.0), temporal(1, false));
  EXPECT_FALSE(renderer.render(frameScene(1, 0.0, 0.0), temporal(1, true)).cloudsReprojected);
}

// A reduced-resolution march is the cheap path already: it runs every frame, no reprojection.
TEST_F(CloudTemporal, ReducedResolutionMarchesEveryFrame) {
  SkyRenderOptions o = temporal(16, false);
  o.clouds.resolutionDivisor = 2;
  test::cloudRenderer().render(frameScene(0, 0.0, 0.0), o);
  o.continueSequence = true;
  const RenderResult r = test::cloudRenderer().render(frameScene(1, 0.0, 0.0), o);
  EXPECT_FALSE(r.cloudsReprojected);
  bool upsampled = false;
  for (const auto& t : r.timings) upsampled = upsampled || t.label == "clouds/upsample_clouds";
  EXPECT_TRUE(upsampled);
}

// A weather scene's sequence: each frame's map is the simulation at that frame's time (scenes without a
// sun section advance /time/utc), so it differs from the last frame's by a little at 30 fps (measured
// 1e-4 in coverage, 3.5 m in top) and the history is kept: the clamp takes the change out. Its last
// frame is as close to a still at that time as the same sequence with the time held is (the jitter
// floor of this dense, 11 km deep storm at 160x90 is high: measured 8.825 % held, 8.824 % moving;
// 22.7 % for both before the empty-space test read the coverage reach);
// allowed 1 point more. A time-lapse's map (60 s per frame) changes by more: that frame marches in full.
TEST_F(CloudTemporal, AWeatherSceneSequenceKeepsItsHistory) {
  SkyRenderer& renderer = test::cloudRenderer();
  auto at = [](double t) {
    return Scene::load(
        test::sourceDir() / "scenes" / "thunderstorm.json",
        {"/weather/grid/cells_x=64", "/weather/grid/cells_y=64", "/camera/width=160", "/camera/height=90",
         "/time/utc=" + astro::formatUtc(astro::addSeconds(astro::parseUtc("2026-06-21T13:30:00Z"), t))});
  };
  const RenderResult still = renderer.render(at(16 / 30.0), temporal(16, false));
  ImageMetrics error[2];
  for (bool moving : {false, true}) {
    RenderResult last;
    for (int i = 0; i < 17; ++i) {
      last = renderer.render(at(moving ? i / 30.0 : 16 / 30.0), temporal(16, i > 0));
      EXPECT_EQ(last.cloudsReprojected, i > 0) << i << (moving ? " moving" : " held");
    }
    error[moving] = compareImages(last.image, still.image);
    std::printf("thunderstorm, 17 frames at 30 fps, time %s: rel RMSE %.3f %%, bias %+.3f %% against a still\n",
                moving ? "moving" : "held", 100.0 * error[moving].luminance.relativeRmse,
                100.0 * error[moving].luminance.relativeMeanBias);
  }
  EXPECT_LT(error[1].luminance.relativeRmse, error[0].luminance.relativeRmse + 0.01);
  EXPECT_LT(std::abs(error[1].luminance.relativeMeanBias), std::abs(error[0].luminance.relativeMeanBias) + 0.002);
  EXPECT_FALSE(renderer.render(at(60.0 + 16 / 30.0), temporal(16, true)).cloudsReprojected);
}

}  // namespace
}  // namespace firmament
