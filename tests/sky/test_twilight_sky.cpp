// The clear sky through dusk (docs/atmosphere.md, "Which model by the sun's altitude"; decision 0158): with
// the sun below the horizon the frame reads Bruneton's 4D tables, whose explicit orders keep the
// directions of the multiply scattered light, instead of the f_ms term that spreads it over the sky; the
// ground's twilight illuminance against the CPU reference, the hand-over between the two models without a
// step, and the plan's choice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "astro/sun.h"
#include "core/color.h"
#include "sky/render_plan.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

// eval/night_bench.cpp's twilight rows: the scenes' place at 1200 m, 2026-06-21 evening.
const astro::GeodeticLocation kPlace = astro::GeodeticLocation::fromDegrees(46.55, 7.98, 1200.0);

// The first minute of the evening of 2026-06-21 with the sun at or below `altitudeDeg`, as the bench finds it.
std::string utcAtSunAltitude(double altitudeDeg, int fromMinute = 16 * 60) {
  char utc[32] = "";
  for (int minute = fromMinute; minute < 23 * 60; ++minute) {
    std::snprintf(utc, sizeof(utc), "2026-06-21T%02d:%02d:00Z", minute / 60, minute % 60);
    if (astro::sunPosition(astro::makeAstroTime(utc), kPlace).elevation() / kDegree <= altitudeDeg) break;
  }
  return utc;
}

Scene fisheyeAt(const std::string& utc, int size) {
  return Scene::parse(R"({"location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200},
                          "time": {"utc": ")" +
                          utc + R"("},
                          "camera": {"height_above_ground_m": 0, "pitch_deg": 90, "fov_deg": 180, "width": )" +
                          std::to_string(size) + R"(, "height": )" + std::to_string(size) +
                          R"(, "projection": "fisheye"}})",
                      "<test>");
}

// The sky's horizontal illuminance read as the bench reads it: the frame at the reference's 10 x 24
// directions (midpoints in mu^2 and azimuth, nearest fisheye pixel), E = pi * mean L.
double groundIlluminance(const RenderResult& r) {
  const shared::CameraParameters& c = r.view.camera;
  double sum = 0.0;
  const int zenithSteps = 10, azimuthSteps = 24;
  for (int i = 0; i < zenithSteps; ++i) {
    const double mu = std::sqrt((i + 0.5) / zenithSteps), z = std::acos(mu);
    for (int j = 0; j < azimuthSteps; ++j) {
      const double az = 2.0 * kPi * (j + 0.5) / azimuthSteps;
      bool valid = false;
      const glm::dvec2 p = shared::cameraPixelOfDirection(
          c, glm::dvec3(std::sin(z) * std::sin(az), std::sin(z) * std::cos(az), std::cos(z)), valid);
      const int x = std::clamp(int(p.x), 0, c.width - 1), y = std::clamp(int(p.y), 0, c.height - 1);
      sum += luminanceRec709(r.image.pixels.data() + (size_t(y) * c.width + x) * 4);
    }
  }
  return kPi * sum / double(zenithSteps * azimuthSteps);
}

class TwilightSkyTest : public test::GpuTest {
 protected:
  static SkyRenderer& renderer() {
    static SkyRenderer r(context());
    return r;
  }
  static SkyRenderOptions options(MultipleScattering form = MultipleScattering::Auto) {
    SkyRenderOptions o;
    o.night.enabled = false;  // the sun's sky alone
    o.multipleScattering = form;
    return o;
  }
};

// The default frame's ground illuminance from the sky at sun -9 and -12 deg against the CPU reference
// (`firmament bench night --scenario twilight --reference-spp 4096`: 0.119 +- 0.010 and 0.0073 +- 0.0022 lx,
// one standard error; the deep twilight is all multiple scattering, heavy-tailed). Allowed: within a factor
// 1.8 either way. That holds the reference's 3 standard errors (25 % at -9 deg, 90 % at -12 deg) and the
// tables' own -42 % at -9 deg (measured 0.069 lx; not their orders, size or steps: decision 0158); f_ms
// alone gives 0.258 and 0.0209 lx (x 2.2, x 2.9) and fails.
TEST_F(TwilightSkyTest, GroundIlluminanceAtMinusNineAndTwelveDegreesIsTheReferences) {
  struct Case {
    double altitude, reference, standardError;
  };
  for (const Case& k : {Case{-9.0, 0.119, 0.010}, Case{-12.0, 0.0073, 0.0022}}) {
    const RenderResult r = renderer().render(fisheyeAt(utcAtSunAltitude(k.altitude), 64), options());
    const double lux = groundIlluminance(r);
    const double low = k.reference / 1.8, high = k.reference * 1.8;
    std::printf("sun %.0f deg: the frame %.4g lx (tables weight %.2f, %d wavelengths), reference %.4g +- %.2g lx\n",
                k.altitude, lux, r.tablesWeight, r.spectralSamples, k.reference, k.standardError);
    EXPECT_EQ(r.tablesWeight, 1.0);
    EXPECT_GT(lux, low) << k.altitude;
    EXPECT_LT(lux, high) << k.altitude;
  }
}

// Through the hand-over (sun -1 to -7 deg every 0.5 deg, a 40 deg view of the zenith): the default
// frame darkens at every step; at and above -2 deg it is the f_ms frame and at and below -6 deg the
// tables' frame, pixel for pixel; and no step of its mean luminance is larger (in log) than the largest
// step of either model alone there, times 1.25 (the sun's motion explains those; switching between the
// models where they disagree would add their ratio, ln 1.19 at -6 deg, to one step).
TEST_F(TwilightSkyTest, HandOverFromFmsToTablesHasNoStep) {
  auto scene = [](const std::string& utc) {
    return Scene::parse(R"({"location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200},
                            "time": {"utc": ")" +
                            utc + R"("},
                            "camera": {"height_above_ground_m": 2, "pitch_deg": 90, "fov_deg": 40, "width": 16,
                                       "height": 16}})",
                        "<test>");
  };
  auto mean = [](const RenderResult& r) {
    double sum = 0.0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) sum += luminanceRec709(r.image.pixels.data() + i * 4);
    return sum / double(r.image.pixelCount());
  };
  // The tables alone: the same tables as the default frame's (its settings, its 12 wavelengths), so the one
  // renderer keeps them (their key has neither the Sun's distance nor the f_ms switch in it).
  SkyRenderOptions tables = options(MultipleScattering::BrunetonTables);
  tables.tables = options().twilightTables;
  tables.luts.spectralSamples = 12;
  std::vector<double> autoL, fmsL, tablesL, altitudes;
  for (double altitude = -1.0; altitude >= -7.0; altitude -= 0.5) {
    const Scene s = scene(utcAtSunAltitude(altitude));
    const RenderResult a = renderer().render(s, options());
    const RenderResult f = renderer().render(s, options(MultipleScattering::HillaireFms));
    const RenderResult t = renderer().render(s, tables);
    const double sun = 90.0 - a.view.sunZenith / kDegree;
    altitudes.push_back(sun);
    autoL.push_back(mean(a));
    fmsL.push_back(mean(f));
    tablesL.push_back(mean(t));
    ASSERT_EQ(a.spectralSamples, 12);
    if (sun >= kTwilightTablesAboveDeg) {
      EXPECT_EQ(a.image.pixels, f.image.pixels) << sun;
    }
    if (sun <= kTwilightTablesBelowDeg) {
      double worst = 0.0;
      for (size_t i = 0; i < a.image.pixels.size(); ++i)
        worst = std::max(
            worst, double(std::fabs(a.image.pixels[i] - t.image.pixels[i]) / std::max(t.image.pixels[i], 1e-30f)));
      EXPECT_LT(worst, 1e-5) << sun;
    }
  }
  double largestAuto = 0.0, largestModels = 0.0;
  for (size_t i = 0; i < altitudes.size(); ++i) {
    std::printf("sun %+5.2f deg: default %.5g, f_ms %.5g, tables %.5g cd/m^2 (tables / f_ms %.3f)\n", altitudes[i],
                autoL[i], fmsL[i], tablesL[i], tablesL[i] / fmsL[i]);
    if (i == 0) continue;
    EXPECT_LT(autoL[i], autoL[i - 1]) << altitudes[i];
    largestAuto = std::max(largestAuto, std::fabs(std::log(autoL[i] / autoL[i - 1])));
    largestModels = std::max(
        {largestModels, std::fabs(std::log(fmsL[i] / fmsL[i - 1])), std::fabs(std::log(tablesL[i] / tablesL[i - 1]))});
  }
  std::printf("largest step of ln L: the default %.4f, the models alone %.4f\n", largestAuto, largestModels);
  EXPECT_LE(largestAuto, 1.25 * largestModels);
}

// The plan (`render --explain`): a daytime clear sky computes no 4D table and says why; a twilight clear
// sky lists them and omits the f_ms sky passes; clouds keep the f_ms path.
TEST(TwilightPlan, DaytimeSkipsTheTablesAndTwilightReadsThem) {
  auto plan = [](const std::string& utc, const std::string& extra = "") {
    return planRender(Scene::parse(R"({"location": {"latitude_deg": 46.55, "longitude_deg": 7.98, "height_m": 1200},
                                       "time": {"utc": ")" +
                                       utc + R"("})" + extra + "}",
                                   "<test>"));
  };
  auto omittedReason = [](const RenderPlan& p, const std::string& prefix) {
    for (const OmittedPass& o : p.omitted)
      if (o.name.rfind(prefix, 0) == 0) return o.reason;
    return std::string();
  };
  const RenderPlan day = plan("2026-06-21T12:00:00Z");
  EXPECT_FALSE(day.has("atmosphere/single_scattering"));
  EXPECT_FALSE(day.has("sky/render_sky_tables"));
  EXPECT_NE(omittedReason(day, "atmosphere/direct_irradiance").find("f_ms alone"), std::string::npos)
      << describePlan(day);
  EXPECT_TRUE(day.has("sky/render_sky"));

  const RenderPlan dusk = plan(utcAtSunAltitude(-8.0));
  EXPECT_TRUE(dusk.has("atmosphere/single_scattering"));
  EXPECT_TRUE(dusk.has("atmosphere/multiple_scattering"));
  EXPECT_TRUE(dusk.has("sky/render_sky_tables"));
  EXPECT_FALSE(dusk.has("sky/render_sky"));
  EXPECT_FALSE(omittedReason(dusk, "sky/sky_view_lut").empty()) << describePlan(dusk);

  const RenderPlan band = plan(utcAtSunAltitude(-4.0));
  EXPECT_TRUE(band.has("sky/render_sky"));
  EXPECT_TRUE(band.has("sky/render_sky_tables"));

  const RenderPlan clouded = plan(utcAtSunAltitude(-8.0), R"(, "clouds": {"layers": [{"kind": "cumulus",
                                  "bottom_m": 1500, "top_m": 2500, "coverage": 0.3}]})");
  EXPECT_FALSE(clouded.has("sky/render_sky_tables"));
  EXPECT_NE(omittedReason(clouded, "atmosphere/direct_irradiance").find("clouds"), std::string::npos);
}

}  // namespace
}  // namespace firmament
