// The night in the frame (sky/night_pass.h): the point-light splat conserves each star's illuminance at
// any resolution, the plan runs the night only below the sun-altitude limit, and a night frame is finite
// and non-negative with the validation layer on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/color.h"
#include "sky/night_pass.h"
#include "sky/render_plan.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

shared::CameraParameters camera(int width, int height, int projection) {
  shared::CameraParameters c{};
  shared::cameraBasis(0.3, 0.4, 0.0, c.forward, c.right, c.up);
  c.fov = 75.0 * kDegree;
  c.yaw = 0.3;
  c.projection = projection;
  c.width = width;
  c.height = height;
  return c;
}

// Sum of radiance x pixel solid angle over the image: the illuminance the splat put there.
double splatIlluminance(const shared::CameraParameters& c, const std::vector<float>& image) {
  double sum = 0.0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x)
      sum += image[(size_t(y) * c.width + x) * 4 + 1] * pixelSolidAngle(c, glm::dvec2(x + 0.5, y + 0.5));
  return sum;
}

TEST(NightFrame, StarSplatConservesIlluminanceAtTwoResolutions) {
  for (int projection :
       {shared::kProjectionPerspective, shared::kProjectionFisheye, shared::kProjectionEquirectangular}) {
    for (int width : {64, 160}) {
      const shared::CameraParameters c = camera(width, width * 9 / 16, projection);
      bool valid = false;
      // A star slightly off the image centre (not on a pixel centre).
      const glm::dvec3 dir = shared::cameraRayDirection(c, glm::dvec2(0.37 * width, 0.61 * c.height), valid);
      ASSERT_TRUE(valid);
      const std::vector<float> image = splatPointLights(c, {{dir, glm::dvec3(2.5e-6)}});
      // Float pixels: 1e-6 relative (measured 1e-7).
      EXPECT_NEAR(splatIlluminance(c, image) / 2.5e-6, 1.0, 1e-5) << projection << " " << width;
    }
  }
}

TEST(NightFrame, PixelSolidAnglesTileTheEquirectangularSphere) {
  const shared::CameraParameters c = camera(64, 32, shared::kProjectionEquirectangular);
  double sum = 0.0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) sum += pixelSolidAngle(c, glm::dvec2(x + 0.5, y + 0.5));
  EXPECT_NEAR(sum / (4.0 * 3.14159265358979323846), 1.0, 1e-3);  // midpoint rule over latitude: 2e-4
}

TEST(NightFrame, PlanRunsTheNightOnlyBelowTheSunAltitudeLimit) {
  const Scene day = Scene::parse(R"({"time": {"utc": "2026-06-21T12:00:00Z"}})", "<test>");
  const Scene night = Scene::parse(R"({"time": {"utc": "2026-06-21T23:00:00Z"}})", "<test>");
  const Scene sunSection = Scene::parse(R"({"sun": {"zenith_deg": 120}})", "<test>");
  EXPECT_FALSE(planRender(day).has("night/night_sky"));
  EXPECT_TRUE(planRender(night).has("night/night_sky"));
  EXPECT_FALSE(planRender(sunSection).has("night/night_sky"));
  bool omitted = false;
  for (const auto& o : planRender(day).omitted)
    omitted = omitted || o.name.find("night/night_sky") != std::string::npos;
  EXPECT_TRUE(omitted);
}

// The daytime Moon (docs/night.md, "The daytime Moon"): with the sun above +10 deg the night's passes are
// omitted and the Moon's disc alone runs, over its pixel rectangle, when the Moon is up and in the view;
// out of the view or below the horizon nothing runs. 2026-06-22T15:00Z at the scenes' place: the sun 42.3
// deg high, a 0.6-lit Moon 23.3 deg high at azimuth 131.2 deg.
TEST(NightFrame, DaytimeMoonRunsItsDiscAloneOnlyWhenUpAndInTheView) {
  const std::string place = R"("location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200})";
  auto plan = [&](const char* utc, double yaw, double pitch) {
    char json[400];
    std::snprintf(json, sizeof(json),
                  R"({%s, "time": {"utc": "%s"}, "camera": {"yaw_deg": %.1f, "pitch_deg": %.1f, "fov_deg": 20}})",
                  place.c_str(), utc, yaw, pitch);
    return planRender(Scene::parse(json, "<test>"));
  };
  const RenderPlan facing = plan("2026-06-22T15:00:00Z", 131.2, 23.3);
  EXPECT_TRUE(facing.has("night/moon_disc_day"));
  EXPECT_FALSE(facing.has("night/night_sky"));
  EXPECT_FALSE(facing.has("night/moon_sky_view (sky/sky_view_lut)"));
  const RenderPlan away = plan("2026-06-22T15:00:00Z", 311.2, 23.3);  // facing the other way
  const RenderPlan set = plan("2026-06-22T08:00:00Z", 131.2, 23.3);   // the Moon below the horizon
  for (const RenderPlan* p : {&away, &set}) {
    EXPECT_FALSE(p->has("night/moon_disc_day"));
    bool omitted = false;
    for (const auto& o : p->omitted) omitted = omitted || o.name == "night/moon_disc_day";
    EXPECT_TRUE(omitted);
  }
  // The rectangle: the disc's circle plus two pixels, clamped to the image; empty out of the view.
  shared::CameraParameters camera{};
  camera.forward = glm::dvec3(0, 1, 0);
  camera.right = glm::dvec3(1, 0, 0);
  camera.up = glm::dvec3(0, 0, 1);
  camera.fov = 2.0 * std::numbers::pi / 180.0;
  camera.width = camera.height = 64;
  const double rho = 0.0045;  // rad: 8.3 pixels of 0.031 deg
  const PixelRect centre = moonDiscPixelRect(camera, camera.forward, rho);
  EXPECT_NEAR(centre.width(), 2.0 * (rho / (camera.fov / 64) + 2.0) + 2.0, 3.0);
  EXPECT_NEAR(0.5 * (centre.x0 + centre.x1), 32.0, 1.0);
  EXPECT_TRUE(moonDiscPixelRect(camera, -camera.forward, rho).empty());
  EXPECT_TRUE(moonDiscPixelRect(camera, glm::dvec3(1, 0, 0), rho).empty());
  // The equirectangular image wraps: a disc on its seam (behind the yaw) spans the whole width, its rows only.
  shared::CameraParameters sphere{};
  sphere.projection = shared::kProjectionEquirectangular;
  sphere.yaw = 0.0;
  sphere.width = 256;
  sphere.height = 128;
  const double rho2 = 0.02;  // rad: 0.8 pixels of 1.4 deg
  const PixelRect seam = moonDiscPixelRect(sphere, glm::normalize(glm::dvec3(0.0, -1.0, 0.3)), rho2);
  EXPECT_EQ(seam.x0, 0);
  EXPECT_EQ(seam.x1, sphere.width);
  EXPECT_LT(seam.height(), 12);
  const PixelRect front = moonDiscPixelRect(sphere, glm::normalize(glm::dvec3(0.0, 1.0, 0.3)), rho2);
  EXPECT_LT(front.width(), 12);
  EXPECT_NEAR(0.5 * (front.x0 + front.x1), 128.0, 2.0);
}

class NightFrameTest : public test::GpuTest {};

TEST_F(NightFrameTest, NightFramesAreFiniteNonNegativeAndDarkerThanDay) {
  static SkyRenderer renderer(context());
  for (const char* utc : {"2026-06-21T21:00:00Z", "2026-06-21T23:00:00Z", "2026-01-03T23:00:00Z"}) {
    const Scene scene = Scene::parse(
        R"({"time": {"utc": ")" + std::string(utc) + R"("}, "camera": {"width": 32, "height": 18, "pitch_deg": 30}})",
        "<test>");
    RenderResult r = renderer.render(scene);
    ASSERT_TRUE(r.night.run) << utc;
    size_t bad = 0;
    double mean = 0.0;
    for (size_t i = 0; i < r.image.pixels.size(); ++i) {
      const float v = r.image.pixels[i];
      bad += !(std::isfinite(v) && v >= 0.0f);
      if (i % 4 == 1) mean += v;
    }
    mean /= double(r.image.pixelCount());
    EXPECT_EQ(bad, 0u) << utc;
    // A night sky: above the moonless dark sky's 2e-4 cd/m^2 (green channel ~ luminance), far below day.
    EXPECT_GT(mean, 1e-4) << utc;
    EXPECT_LT(mean, 10.0) << utc;
  }
}

}  // namespace
}  // namespace firmament

namespace firmament {
namespace {

// Leinert et al. 1998: the moonless zenith at a dark site is 21.6-22.0 V mag/arcsec^2 at the ground
// (1.0807e5 cd/m^2 at 0 mag/arcsec^2, docs/night.md "Units"). New Moon, the zenith near the galactic pole (April, 22:00
// UTC), stars left out (the catalogue's stars are points, not the diffuse sky), a 10° view of the zenith from sea
// level.
TEST_F(NightFrameTest, MoonlessDarkSiteZenithIsInLeinertsRangeAtTheGround) {
  static SkyRenderer renderer(context());
  const Scene scene = Scene::parse(
      R"({"location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 0},
          "time": {"utc": "2026-04-17T22:00:00Z"},
          "camera": {"width": 16, "height": 16, "pitch_deg": 90, "fov_deg": 10}})",
      "<test>");
  SkyRenderOptions options;
  options.night.stars = false;
  RenderResult r = renderer.render(scene, options);
  ASSERT_TRUE(r.night.run);
  EXPECT_FALSE(r.night.moonSky);  // the new Moon is below the horizon
  double sum = 0.0;
  for (size_t i = 0; i < r.image.pixelCount(); ++i) sum += luminanceRec709(r.image.pixels.data() + i * 4);
  const double magnitude = -2.5 * std::log10(sum / double(r.image.pixelCount()) / 1.0807e5);
  std::printf("dark-site zenith at the ground: %.3f mag/arcsec^2\n", magnitude);
  EXPECT_GT(magnitude, 21.6);
  EXPECT_LT(magnitude, 22.0);
}

}  // namespace
}  // namespace firmament
