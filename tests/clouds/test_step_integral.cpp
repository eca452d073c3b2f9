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
  EXPECT_EQ(shared::cloudStepIntegral(0.0, 7.0), 7.0);         // no medium: S dt
  EXPECT_NEAR(shared::cloudStepIntegral(1e-10, 7.0), 7.0, 7.0 * 1e-9);
  EXPECT_EQ(shared::cloudStepIntegral(1e4, 1.0), 1.0 / 1e4);   // opaque: S / sigma_t
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
    sum += w * shared::cloudPhase(0.8, -0.3, 0.3, nu);
  }
  EXPECT_NEAR(2.0 * shared::kPi * sum * (2.0 / n) / 3.0, 1.0, 1e-4);
}

}  // namespace
}  // namespace firmament
