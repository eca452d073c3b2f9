// The Eddington diffusion floor of the octave model (common/cloud_lighting.glsl
// cloudEddingtonSlabSource) on the CPU in double: the slab solution's own conditions, checked from the
// values it returns (I0 from muDown = 0, I1 from the difference between muDown = +-0.1, where
// I0 +- 0.1 g I1 stays positive and nothing is clamped).
#include <gtest/gtest.h>

#include <cmath>

#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Moments {
  double i0, i1;
};

// I0 and I1 per unit solar irradiance at depth tau.
Moments moments(double mu0, double tau, double tauTotal, double g) {
  const double i0 = shared::cloudEddingtonSlabSource(mu0, tau, tauTotal, g, 0.0);
  const double plus = shared::cloudEddingtonSlabSource(mu0, tau, tauTotal, g, 0.1);
  const double minus = shared::cloudEddingtonSlabSource(mu0, tau, tauTotal, g, -0.1);
  EXPECT_GT(plus, 0.0);
  EXPECT_GT(minus, 0.0);
  return {i0, (plus - minus) / (0.2 * g)};
}

TEST(CloudDiffusionFloor, ConservesTheNetFluxThroughTheSlab) {
  // Conservative scattering: the net downward flux, diffuse (4 pi / 3) I1 plus direct mu0 E e^(-tau/mu0),
  // is the same at every depth.
  for (double mu0 : {0.2, 0.5, 0.9})
    for (double tauTotal : {2.0, 10.0, 40.0}) {
      const double g = 0.8;
      auto net = [&](double tau) {
        return 4.0 * kPi / 3.0 * moments(mu0, tau, tauTotal, g).i1 + mu0 * std::exp(-tau / mu0);
      };
      const double reference = net(0.5 * tauTotal);
      for (double f : {0.25, 0.75, 1.0})
        EXPECT_NEAR(net(f * tauTotal), reference, 1e-9) << mu0 << " " << tauTotal << " " << f;
      // Transmitted: between 0 and the incident flux mu0 E (no energy gain).
      EXPECT_GT(reference, 0.0);
      EXPECT_LT(reference, mu0);
    }
}

TEST(CloudDiffusionFloor, MeetsTheBoundaryConditions) {
  const double mu0 = 0.6, g = 0.8, tauTotal = 20.0;
  // Black ground below: no diffuse light upwards at the base, I0 - 2/3 I1 = 0.
  const Moments base = moments(mu0, tauTotal, tauTotal, g);
  EXPECT_NEAR(base.i0 - 2.0 / 3.0 * base.i1, 0.0, 1e-12);
  EXPECT_GT(base.i0, 0.0);
  // Linear in depth inside (diffusion): equal steps, equal drops, the drop (1 - g) I1 (up to the direct
  // beam's source, e^(-8 / 0.6) ~ 2e-6 of it at these depths).
  const double a = moments(mu0, 8.0, tauTotal, g).i0, b = moments(mu0, 10.0, tauTotal, g).i0,
               c = moments(mu0, 12.0, tauTotal, g).i0;
  EXPECT_NEAR(a - b, b - c, 1e-6);
  EXPECT_NEAR(a - b, 2.0 * (1.0 - g) * moments(mu0, 10.0, tauTotal, g).i1, 1e-6);
}

TEST(CloudDiffusionFloor, VanishesWithoutASlabOrASun) {
  EXPECT_NEAR(shared::cloudEddingtonSlabSource(0.7, 0.0, 1e-9, 0.8, 0.0), 0.0, 1e-9);
  EXPECT_EQ(shared::cloudEddingtonSlabSource(0.0, 5.0, 10.0, 0.8, 0.5), 0.0);
  EXPECT_EQ(shared::cloudEddingtonSlabSource(-0.3, 5.0, 10.0, 0.8, 0.5), 0.0);
  // Finite and non-negative over stiff cases: grazing and high suns, vanishing and huge depths.
  for (double mu0 : {1e-4, 0.01, 0.1, 1.0})
    for (double tau : {0.0, 1e-6, 1.0, 1e4})
      for (double muDown : {-1.0, 0.0, 1.0}) {
        const double v = shared::cloudEddingtonSlabSource(mu0, tau, 2.0 * tau + 1e-3, 0.85, muDown);
        EXPECT_TRUE(std::isfinite(v));
        EXPECT_GE(v, 0.0);
      }
}

TEST(CloudDiffusionFloor, PhaseMeanCosineIsTheIntegral) {
  // <nu> = integral of p(nu) nu dOmega, by the midpoint rule, for dual HG and an approximate-Mie lobe pair.
  for (const auto& lobes : {std::array<double, 4>{0.8, -0.2, 0.25, 0.0}, std::array<double, 4>{0.9, 0.4, 0.3, 0.6}}) {
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double nu = -1.0 + (i + 0.5) * 2.0 / n;
      sum += shared::cloudPhase(lobes[0], lobes[1], lobes[2], lobes[3], nu) * nu * 2.0 * kPi * (2.0 / n);
    }
    EXPECT_NEAR(shared::cloudPhaseMeanCosine(lobes[0], lobes[1], lobes[2], lobes[3]), sum, 1e-4);
  }
}

}  // namespace
}  // namespace firmament
