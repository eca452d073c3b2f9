// The energy-conserving step integral (common/cloud_lighting.glsl) on the CPU in double: exact in the
// thin and thick limits and accurate everywhere between, over sigma_t dt from 1e-8 to 1e4.
#include <gtest/gtest.h>

#include <cmath>

#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

TEST(CloudStepIntegral, MatchesExpm1FromThinToOpaque) {
  const double dt = 10.0;
  for (double k = 1e-8; k <= 1e4 * 1.0001; k *= 1.25) {
    const double sigma = k / dt;
    const double exact = -std::expm1(-k) / sigma;  // (1 - e^-k) / sigma_t without cancellation
    const double value = shared::cloudStepIntegral(sigma, dt);
    ASSERT_TRUE(std::isfinite(value)) << k;
    EXPECT_NEAR(value / exact, 1.0, 1e-12) << "k = " << k;
  }
}

TEST(CloudStepIntegral, ExactLimits) {
  EXPECT_EQ(shared::cloudStepIntegral(0.0, 7.0), 7.0);  // no medium: S dt
  EXPECT_NEAR(shared::cloudStepIntegral(1e-10, 7.0), 7.0, 7.0 * 1e-9);
  EXPECT_EQ(shared::cloudStepIntegral(1e4, 1.0), 1.0 / 1e4);  // opaque: S / sigma_t
  EXPECT_EQ(shared::cloudStepIntegral(1e3, 100.0), 1.0 / 1e3);
  // Energy: never more than the thin-medium S dt, never more than the opaque S / sigma_t.
  for (double k = 1e-8; k < 1e4; k *= 3.0) {
    EXPECT_LE(shared::cloudStepIntegral(k, 1.0), 1.0 + 1e-15);
    EXPECT_LE(shared::cloudStepIntegral(k, 1.0), 1.0 / k * (1.0 + 1e-15));
  }
}

TEST(CloudPhase, DualLobeIsNormalised) {
  // ∫ p dOmega = 2 pi ∫_{-1}^{1} p(nu) dnu, Simpson's rule on 20001 points.
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double nu = -1.0 + 2.0 * i / n;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * shared::cloudPhase(0.8, -0.3, 0.3, 0.0, nu);
  }
  EXPECT_NEAR(2.0 * shared::kPi * sum * (2.0 / n) / 3.0, 1.0, 1e-4);
}

}  // namespace
}  // namespace firmament

namespace firmament {
namespace {

// The light march's length (common/cloud_lighting.glsl cloudSunExitDistance): from a point inside a
// shell to where a ray leaves it, through the top or the base, capped. A grazing sun crosses a layer
// over about H / cos(theta_s): the first milestone marched one thickness whatever the sun.
TEST(CloudSunExitDistance, TopBaseGrazingAndCap) {
  const double ground = 6360e3;
  shared::CloudLayer layer{};
  layer.bottom_radius = ground + 1000.0;
  layer.top_radius = ground + 2000.0;
  const glm::dvec3 p(0.0, 0.0, ground + 1500.0);
  EXPECT_NEAR(shared::cloudSunExitDistance(layer, p, glm::dvec3(0.0, 0.0, 1.0), 1e5), 500.0, 1e-6);   // up
  EXPECT_NEAR(shared::cloudSunExitDistance(layer, p, glm::dvec3(0.0, 0.0, -1.0), 1e5), 500.0, 1e-6);  // down
  const double theta = 85.0 * 3.14159265358979323846 / 180.0;
  const glm::dvec3 low(std::sin(theta), 0.0, std::cos(theta));
  const double exit = shared::cloudSunExitDistance(layer, p, low, 1e5);
  // Exact: the root of |p + t s| = r_top; the flat-layer estimate 500 / cos(85 deg) = 5737 m is a
  // little longer (the shell curves down towards the ray).
  const double r = glm::length(p), mu = glm::dot(p, low) / r, top = layer.top_radius;
  const double exact = -r * mu + std::sqrt(top * top - r * r * (1.0 - mu * mu));
  EXPECT_NEAR(exit, exact, 1e-6 * exact);
  EXPECT_GT(exit, 5000.0);
  EXPECT_LT(exit, 500.0 / std::cos(theta));
  EXPECT_NEAR(shared::cloudSunExitDistance(layer, p, low, 3000.0), 3000.0, 1e-9);  // capped
  // Horizontal ray from the middle of the shell: it leaves through the top, sqrt(r_top^2 - r^2) = 79.8 km away.
  EXPECT_NEAR(shared::cloudSunExitDistance(layer, p, glm::dvec3(1.0, 0.0, 0.0), 1e6), std::sqrt(top * top - r * r),
              1e-3);
}

// The bound that lets the march skip the way down from the layer top: no optical depth passes more of
// an octave than cloudOctaveTransmittanceBound, and the bound is reached (so the skip is as often as it
// can be). Scanned over tau in [0, 1e4] on a log grid of 20 000 points around the analytic maximum.
TEST(CloudOctaveBound, NoDepthExceedsItAndItIsReached) {
  for (bool scatteredOnly : {true, false})
    for (double s : {1e-6, 1e-3, 0.05, 0.272, 0.5, 0.9, 0.999}) {
      const double bound = shared::cloudOctaveTransmittanceBound(s, scatteredOnly);
      double highest = 0.0;
      for (int i = 0; i <= 20000; ++i) {
        const double tau = i == 0 ? 0.0 : 1e-6 * std::pow(1e10, double(i) / 20000.0);
        highest = std::max(highest, shared::cloudOctaveTransmittance(s, tau, scatteredOnly));
      }
      EXPECT_LE(highest, bound * (1.0 + 1e-12)) << s << " " << scatteredOnly;
      EXPECT_GE(highest, bound * (1.0 - 1e-3)) << s << " " << scatteredOnly;
    }
  EXPECT_EQ(shared::cloudOctaveTransmittanceBound(0.0, true), 1.0);
  EXPECT_EQ(shared::cloudOctaveTransmittanceBound(1.0, true), 0.0);
  EXPECT_EQ(shared::cloudOctaveTransmittanceBound(1.5, true), 0.0);
}

// Octave i scales by a^i, b^i, c^i with 0^0 = 1: the stratus fit has c = 0, and the shader's former
// pow(0, 0) was NaN on an NVIDIA GPU (undefined in GLSL). The products equal pow to rounding.
TEST(CloudOctavePower, ZeroToTheZeroIsOneAndOtherwiseMatchesPow) {
  EXPECT_EQ(shared::cloudOctavePower(0.0, 0), 1.0);
  EXPECT_EQ(shared::cloudOctavePower(0.0, 3), 0.0);
  EXPECT_EQ(shared::cloudOctaveEccentricityScale(0.0, 0), 1.0);
  for (double x : {1e-3, 0.347, 0.538, 0.966, 1.0})
    for (int i = 0; i <= 8; ++i)
      EXPECT_NEAR(shared::cloudOctavePower(x, i), std::pow(x, double(i)), 1e-15) << x << " " << i;
}

}  // namespace
}  // namespace firmament
