// The higher orders' build-up along the view (common/cloud_lighting.glsl cloudBuildUpDecay and
// cloudBuildUpStepWeight), run on the CPU in double exactly as the march runs it: a running sum R of
// the steps' light of orders >= 2, taken off at the end. Checked against the closed form for a
// homogeneous cloud with a uniform source, and for stability over steps of optical depth 1e-8 to 1e4.
#include <gtest/gtest.h>

#include <cmath>

#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

// A ray through a homogeneous cloud of optical depth tau with source J = 1 of orders >= 2, in `steps`
// equal steps (the march's order of operations): the light with the build-up and without it.
struct Marched {
  double withBuildUp, without;
};
Marched march(double tau, double k, int steps) {
  const double dTau = tau / steps;
  double transmittance = 1.0, sum = 0.0, lost = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double c = transmittance * shared::cloudStepIntegral(1.0, dTau);  // sigma_t 1 per unit optical depth
    sum += c;
    lost = lost * shared::cloudBuildUpDecay(k, dTau) + c * shared::cloudBuildUpStepWeight(k, dTau);
    transmittance *= std::exp(-dTau);
  }
  return {sum - lost, sum};
}

// The closed form: integral over t in [0, tau] of e^-t (1 - e^(-k (tau - t))) dt.
double closedForm(double tau, double k) {
  if (std::abs(k - 1.0) < 1e-12) return -std::expm1(-tau) - tau * std::exp(-tau);
  return -std::expm1(-tau) - (std::exp(-tau) - std::exp(-k * tau)) / (k - 1.0);
}

TEST(CloudBuildUp, MatchesTheClosedFormForAHomogeneousCloud) {
  // Midpoint weights: the error falls as 1 / steps^2; 400 steps hold it within 1e-4 relative.
  for (double k : {1.0, 2.0, 4.0, 10.0})
    for (double tau : {0.01, 0.1, 1.0, 5.0, 30.0}) {
      const Marched m = march(tau, k, 400);
      EXPECT_NEAR(m.withBuildUp / closedForm(tau, k), 1.0, 1e-4) << "k " << k << " tau " << tau;
      EXPECT_NEAR(m.without / -std::expm1(-tau), 1.0, 1e-12) << "k " << k << " tau " << tau;
    }
}

TEST(CloudBuildUp, ThinCloudsGrowAsTauSquaredThickOnesKeepTheirLight) {
  const double k = 4.0;
  // tau << 1: about k tau^2 / 2 (second order), against tau without the build-up.
  for (double tau : {1e-3, 1e-2}) EXPECT_NEAR(march(tau, k, 200).withBuildUp / (0.5 * k * tau * tau), 1.0, 0.03) << tau;
  // tau >> 1: the light comes from the front, with a thick cloud behind it: all kept, within 1e-6.
  const Marched thick = march(40.0, k, 4000);
  EXPECT_NEAR(thick.withBuildUp / thick.without, 1.0, 1e-6);
  // The factor only takes light off, and more of it for a smaller k.
  for (double tau : {0.05, 0.5, 3.0}) {
    double previous = 0.0;
    for (double kk : {0.5, 1.0, 2.0, 4.0, 8.0, 100.0}) {
      const Marched m = march(tau, kk, 100);
      EXPECT_GE(m.withBuildUp, 0.0);
      EXPECT_LE(m.withBuildUp, m.without * (1.0 + 1e-12));
      EXPECT_GT(m.withBuildUp, previous) << "tau " << tau << " k " << kk;
      previous = m.withBuildUp;
    }
  }
}

TEST(CloudBuildUp, StableFromThinToOpaqueSteps) {
  // Steps of optical depth 1e-8 to 1e4, many of them: no NaN, no Inf, no negative light, never more
  // than without the build-up (the running sum's factors are all at most 1).
  for (double dTau = 1e-8; dTau <= 1e4; dTau *= 10.0)
    for (double k : {0.25, 4.0, 1e3}) {
      const Marched m = march(dTau * 1000.0, k, 1000);
      ASSERT_TRUE(std::isfinite(m.withBuildUp)) << dTau << " " << k;
      EXPECT_GE(m.withBuildUp, 0.0) << dTau << " " << k;
      EXPECT_LE(m.withBuildUp, m.without * (1.0 + 1e-12)) << dTau << " " << k;
    }
  EXPECT_EQ(shared::cloudBuildUpDecay(4.0, 0.0), 1.0);
  EXPECT_EQ(shared::cloudBuildUpStepWeight(4.0, 0.0), 1.0);
  EXPECT_EQ(shared::cloudBuildUpDecay(4.0, 1e6), 0.0);
  EXPECT_EQ(shared::cloudBuildUpDecay(4.0, -1.0), 1.0);  // a negative step (rounding) adds no light
}

}  // namespace
}  // namespace firmament
