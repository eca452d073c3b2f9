// The light the cloud behind a sample turns back towards the sun (common/cloud_lighting.glsl
// cloudReflectedSource) on the CPU in double: its limits, bounds and monotony, from which the march's
// use of it cannot add energy beyond its weight r times a normalised lobe.
#include <gtest/gtest.h>

#include <cmath>

#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(CloudReflectedLight, VanishesWithoutMediumBehindAndLooksBackTowardsTheSun) {
  // A thin wisp (nothing behind) reflects nothing, at any depth and angle.
  for (double nu : {-1.0, 0.0, 1.0}) EXPECT_EQ(shared::cloudReflectedSource(0.0, 3.0, 0.47, 0.5, nu), 0.0);
  // Looking straight at the sun (nu = 1) the light going back towards it is not seen.
  EXPECT_EQ(shared::cloudReflectedSource(50.0, 0.0, 0.47, 0.5, 1.0), 0.0);
  // The lobe (1 - nu) / 4pi integrates to 1 over the sphere (midpoint rule in nu).
  double integral = 0.0;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    const double nu = -1.0 + (i + 0.5) * 2.0 / n;
    integral += 2.0 * kPi * (1.0 - nu) / (4.0 * kPi) * (2.0 / n);
  }
  EXPECT_NEAR(integral, 1.0, 1e-12);
}

TEST(CloudReflectedLight, GrowsWithTheMediumBehindTowardsTheSlabReflectance) {
  // s tau / (4/3 + s tau): 0 at tau = 0, half at s tau = 4/3, below 1 at any depth, rising.
  const double g = 0.47, s = 1.0 - g;
  const double full = 2.0 / (4.0 * kPi);  // the lobe at nu = -1, reflectance 1, at the lit surface
  EXPECT_NEAR(shared::cloudReflectedSource(4.0 / 3.0 / s, 0.0, g, 0.5, -1.0), 0.5 * full, 1e-15);
  double previous = 0.0;
  for (double tauBehind : {1e-8, 1e-3, 0.1, 1.0, 10.0, 1e3, 1e8}) {
    const double v = shared::cloudReflectedSource(tauBehind, 0.0, g, 0.5, -1.0);
    EXPECT_GT(v, previous) << tauBehind;
    EXPECT_LT(v, full) << tauBehind;
    previous = v;
  }
  EXPECT_NEAR(previous, full, 1e-7 * full);
}

TEST(CloudReflectedLight, FallsWithTheDepthFromTheSunAndStaysFinite) {
  // exp(-a_r tau_sun): a_r = 0 keeps it, a_r = 1 halves it at tau = ln 2.
  const double atSurface = shared::cloudReflectedSource(5.0, 0.0, 0.47, 1.0, -0.3);
  EXPECT_NEAR(shared::cloudReflectedSource(5.0, std::log(2.0), 0.47, 1.0, -0.3), 0.5 * atSurface, 1e-15);
  EXPECT_EQ(shared::cloudReflectedSource(5.0, 40.0, 0.47, 0.0, -0.3), atSurface);
  // Extreme depths and the clamp of negative inputs (rounding in the map's difference).
  for (double tauBehind : {-1.0, 0.0, 1e-8, 1e4})
    for (double tauSun : {-1.0, 0.0, 1e-8, 1e4})
      for (double g : {-0.3, 0.0, 0.47, 0.99}) {
        const double v = shared::cloudReflectedSource(tauBehind, tauSun, g, 1.0, -1.0);
        EXPECT_TRUE(std::isfinite(v));
        EXPECT_GE(v, 0.0);
        EXPECT_LE(v, 2.0 / (4.0 * kPi));
      }
}

// Under the low-sun scale s (cloudOctaveLowSunScale) the depth scale is a_r / s
// (cloudReflectedLowSunDepthScale): a_r itself for suns above mu_0 (s = 1: bit for bit), and the source
// falls as the sun lowers at any depth from it but the surface; finite for a sun at the horizon (s = 0).
TEST(CloudReflectedLight, LowSunDepthScaleLeavesHighSunsAndFallsAsTheSunLowers) {
  const double aR = 0.043, mu0 = 0.358;
  EXPECT_EQ(shared::cloudReflectedLowSunDepthScale(aR, shared::cloudOctaveLowSunScale(0.5, mu0)), aR);
  EXPECT_EQ(shared::cloudReflectedLowSunDepthScale(aR, shared::cloudOctaveLowSunScale(0.9, 0.0)), aR);  // scale off
  EXPECT_NEAR(shared::cloudReflectedLowSunDepthScale(aR, 0.5), 2.0 * aR, 1e-15);
  const double atHorizon = shared::cloudReflectedLowSunDepthScale(aR, shared::cloudOctaveLowSunScale(0.0, mu0));
  EXPECT_TRUE(std::isfinite(atHorizon));
  EXPECT_GE(atHorizon, aR);
  for (double tauSun : {0.0, 1.0, 10.0, 1e4}) {
    double previous = 1e300;
    for (double muS : {0.6, 0.358, 0.3, 0.2, 0.1, 0.01, 0.0}) {
      const double s = shared::cloudOctaveLowSunScale(muS, mu0);
      const double v =
          s * shared::cloudReflectedSource(5.0, tauSun, 0.47, shared::cloudReflectedLowSunDepthScale(aR, s), -0.5);
      EXPECT_TRUE(std::isfinite(v));
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, previous);
      if (tauSun > 0.0 && muS < mu0 && muS > 0.0) {
        EXPECT_LT(v, s * shared::cloudReflectedSource(5.0, tauSun, 0.47, aR, -0.5));
      }
      previous = v;
    }
  }
}

}  // namespace
}  // namespace firmament
