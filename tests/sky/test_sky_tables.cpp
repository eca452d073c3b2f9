// The two multiple-scattering forms of the clear-sky render on the GPU (lavapipe in CI), with zero
// validation messages (GpuTest): Bruneton 2017's 4D tables against Hillaire 2020's f_ms path at noon,
// convergence over scattering orders, any camera altitude, and twilight without steps.
// The tables are smaller than the defaults (8 x 16 x 64 x 16) so the suite stays short.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/color.h"
#include "sky/sky_renderer.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class SkyTablesTest : public test::GpuTest {
 protected:
  // One renderer per form, so each keeps its own cached tables.
  static SkyRenderer& renderer(MultipleScattering form) {
    static SkyRenderer fms(context());
    static SkyRenderer tables(context());
    return form == MultipleScattering::HillaireFms ? fms : tables;
  }
  static SkyRenderOptions options(MultipleScattering form, int orders = 4) {
    SkyRenderOptions o;
    o.multipleScattering = form;
    o.tables.scatteringOrders = orders;
    o.tables.muSSize = 16;
    o.tables.muSize = 64;
    o.tables.rSize = 16;
    return o;
  }
  static RenderResult render(MultipleScattering form, std::vector<std::string> overrides, int width, int height,
                             int orders = 4) {
    overrides.push_back("/camera/width=" + std::to_string(width));
    overrides.push_back("/camera/height=" + std::to_string(height));
    Scene scene = Scene::parse("{}", "<test>", overrides);
    return renderer(form).render(scene, options(form, orders));
  }
  static size_t badPixels(const Image& image) {
    size_t bad = 0;
    for (float v : image.pixels) bad += !(std::isfinite(v) && v >= 0.0f);
    return bad;
  }
  static double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.pixelCount(); ++i) sum += luminanceRec709(image.pixels.data() + i * 4);
    return sum / double(image.pixelCount());
  }
  static const char* name(MultipleScattering form) {
    return form == MultipleScattering::HillaireFms ? "fms" : "tables";
  }
};

constexpr MultipleScattering kForms[] = {MultipleScattering::HillaireFms, MultipleScattering::BrunetonTables};

TEST_F(SkyTablesTest, PlanMatchesWhatRuns) {
  RenderResult r = render(MultipleScattering::BrunetonTables, {"/sun/zenith_deg=40"}, 16, 8);
  EXPECT_TRUE(r.plan.has("sky/render_sky_tables"));
  EXPECT_FALSE(r.plan.has("atmosphere/multiple_scattering_lut"));
  EXPECT_FALSE(r.plan.has("sky/render_sky"));
  RenderResult f = render(MultipleScattering::HillaireFms, {"/sun/zenith_deg=40"}, 16, 8);
  EXPECT_TRUE(f.plan.has("atmosphere/multiple_scattering_lut"));
  EXPECT_TRUE(f.plan.has("atmosphere/fms_sky_irradiance"));
  EXPECT_FALSE(f.plan.has("atmosphere/single_scattering"));
  // Every GPU pass that ran is in the plan (the tables ran: this is the first render of each form,
  // or they are reused and only the render pass ran).
  for (const RenderResult* result : {&r, &f})
    for (const auto& t : result->timings) EXPECT_TRUE(result->plan.has(t.label)) << t.label;
}

// Noon (sun zenith 30 deg), the default view (looking 8 deg up, horizon and ground in view): the two
// forms agree within 5 % in mean luminance and 8 % in mean per-pixel relative difference. They are
// different approximations of the same physics (f_ms: isotropic, infinite orders, a 32-step march;
// tables: exact phase functions, 4 orders, table interpolation), so they need not agree exactly.
TEST_F(SkyTablesTest, TablesAgreeWithFmsAtNoon) {
  RenderResult f = render(MultipleScattering::HillaireFms, {"/sun/zenith_deg=30"}, 64, 36);
  RenderResult t = render(MultipleScattering::BrunetonTables, {"/sun/zenith_deg=30"}, 64, 36);
  ASSERT_EQ(badPixels(f.image), 0u);
  ASSERT_EQ(badPixels(t.image), 0u);
  double sumRelative = 0.0, worst = 0.0;
  for (size_t i = 0; i < f.image.pixelCount(); ++i) {
    double yf = luminanceRec709(f.image.pixels.data() + i * 4);
    double yt = luminanceRec709(t.image.pixels.data() + i * 4);
    double relative = std::abs(yt - yf) / std::max(yf, 1e-3);
    sumRelative += relative;
    worst = std::max(worst, relative);
  }
  double meanRelative = sumRelative / double(f.image.pixelCount());
  double meanF = meanLuminance(f.image), meanT = meanLuminance(t.image);
  std::printf("noon: mean luminance fms %.1f, tables %.1f cd/m2 (%.2f %%); mean |relative| %.2f %%, worst %.2f %%\n",
              meanF, meanT, 100.0 * (meanT / meanF - 1.0), 100.0 * meanRelative, 100.0 * worst);
  EXPECT_NEAR(meanT / meanF, 1.0, 0.05);
  EXPECT_LT(meanRelative, 0.08);
}

// Orders 1..5: the luminance each order adds to a noon view shrinks geometrically (each increment
// below 0.6 of the previous one; measured 0.19-0.25), so truncating at N orders leaves at most
// increment_N * 0.6 / 0.4. Tables of 8 x 16 x 32 x 8 keep the five precomputations short.
TEST_F(SkyTablesTest, OrdersConverge) {
  SkyRenderer renderer(context());
  Scene scene = Scene::parse("{}", "<test>", {"/sun/zenith_deg=30", "/camera/width=32", "/camera/height=18"});
  std::vector<double> mean;
  for (int orders = 1; orders <= 5; ++orders) {
    SkyRenderOptions o = options(MultipleScattering::BrunetonTables, orders);
    o.tables.muSize = 32;
    o.tables.rSize = 8;
    RenderResult r = renderer.render(scene, o);
    ASSERT_EQ(badPixels(r.image), 0u) << orders;
    mean.push_back(meanLuminance(r.image));
  }
  for (size_t n = 2; n < mean.size(); ++n) {
    double previous = mean[n - 1] - mean[n - 2];
    double increment = mean[n] - mean[n - 1];
    std::printf("order %zu adds %.3f cd/m2 (%.3f of order %zu's)\n", n + 1, increment, increment / previous, n);
    EXPECT_GT(increment, 0.0);
    EXPECT_LT(increment, 0.6 * previous) << "order " << n + 1;
  }
}

TEST_F(SkyTablesTest, AnyCameraAltitudeIsFiniteAndNonNegative) {
  for (MultipleScattering form : kForms)
    for (const char* height : {"-100", "0", "10000", "100000", "1000000", "100000000"}) {
      RenderResult r = render(form,
                              {std::string("/camera/height_above_ground_m=") + height, "/camera/pitch_deg=-30",
                               "/camera/projection=equirectangular", "/sun/zenith_deg=60"},
                              32, 16);
      EXPECT_EQ(badPixels(r.image), 0u) << name(form) << " camera height " << height;
      // From 1e8 m the planet (3.6 deg wide) falls between the pixels: only below 1000 km is it seen.
      if (std::atof(height) <= 1e6) {
        EXPECT_GT(meanLuminance(r.image), 0.0) << name(form) << " camera height " << height;
      }
    }
}

// Sun zenith 85..110 deg in 0.5 deg steps, a fixed view towards the sun's azimuth (8 deg up, 90 deg
// wide, horizon and ground in view): every pixel finite and non-negative, and the mean luminance
// falls smoothly. Smoothness is judged on the logarithm, where twilight's near-exponential fall is a
// straight line: between neighbours the mean never rises (0.1 % slack), and the slope
// ln(L_i / L_{i+1}) changes by at most 0.25 between consecutive steps (a step in luminance, e.g. from
// a truncated order switching off or a table clamp, would show as a spike in the slope). Points more
// than 1e6 times darker than at 85 deg (~2e-3 cd/m^2, the end of twilight) are not judged.
// Measured largest slope change: 0.22 (fms, at 103 deg, where the last sunlit air leaves the view)
// and 0.17 (tables, whose mu_s axis is interpolated geometrically; linearly it reached 1.5).
TEST_F(SkyTablesTest, TwilightHasNoSteps) {
  for (MultipleScattering form : kForms) {
    std::vector<double> mean;
    for (int i = 0; i <= 50; ++i) {
      double zenith = 85.0 + 0.5 * i;
      RenderResult r = render(form,
                              {"/sun/zenith_deg=" + std::to_string(zenith), "/sun/azimuth_deg=90", "/camera/yaw_deg=90",
                               "/camera/pitch_deg=8", "/camera/fov_deg=90"},
                              24, 12);
      ASSERT_EQ(badPixels(r.image), 0u) << name(form) << " sun zenith " << zenith;
      mean.push_back(meanLuminance(r.image));
    }
    const double floor = mean[0] * 1e-6;
    double previousSlope = std::nan("");
    for (size_t i = 0; i + 1 < mean.size(); ++i) {
      double zenith = 85.0 + 0.5 * double(i);
      EXPECT_LE(mean[i + 1], mean[i] * 1.001 + 1e-12) << name(form) << " from " << zenith;
      if (mean[i + 1] < floor) break;
      double slope = std::log(mean[i] / mean[i + 1]);
      std::printf("%s %.1f deg: %.6g cd/m2, slope %.3f\n", name(form), zenith, mean[i], slope);
      if (!std::isnan(previousSlope)) {
        EXPECT_LT(std::abs(slope - previousSlope), 0.25) << name(form) << " at " << zenith;
      }
      previousSlope = slope;
    }
  }
}

}  // namespace
}  // namespace firmament
