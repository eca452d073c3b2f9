// The light of the octaves i >= 1 through the other layers (common/cloud_lighting.glsl
// cloudSlabTransmission, cloudDeckDiffuseLight, cloudOctaveTransmittanceThroughOthers) on the CPU in double: the slab's
// transmission against the diffusion floor's own two-stream solution and against the photon Monte Carlo of
// a slab (clouds/slab_monte_carlo.h), its limits, and the octave's attenuation that it bounds from below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clouds/cloud_settings.h"
#include "clouds/slab_monte_carlo.h"
#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The flux out of the base of a slab of vertical optical depth tauTotal per unit incident flux mu0 E,
// from cloudEddingtonSlabSource's moments there (tests/clouds/test_cloud_diffusion.cpp checks they
// conserve the net flux and meet the boundary conditions): the diffuse (4 pi / 3) I1 (the base's
// upward diffuse flux is 0: black ground) plus the direct mu0 e^(-tauTotal / mu0).
double baseFlux(double mu0, double tauTotal, double g) {
  const double plus = shared::cloudEddingtonSlabSource(mu0, tauTotal, tauTotal, g, 0.1);
  const double minus = shared::cloudEddingtonSlabSource(mu0, tauTotal, tauTotal, g, -0.1);
  const double i1 = (plus - minus) / (0.2 * g);
  return (4.0 * kPi / 3.0 * i1 + mu0 * std::exp(-tauTotal / mu0)) / mu0;
}

// The corrections the floor takes (cloudFloorSunFactor), capped at 1.
double floorCorrection(double mu0) { return std::min(shared::cloudFloorSunFactor(std::max(mu0, 0.02)), 1.0); }

TEST(CloudDeckTransmission, IsTheDiffusionFloorsSlabTransmission) {
  // tauSlant along the sun is mu0 tauSlant vertically. g <= 0.6 keeps mu0 g <= 2/3 (no clamp at 1).
  // The direct beam as it is, the diffuse part with the floor's corrections.
  for (double mu0 : {0.1, 0.4, 0.9})
    for (double g : {0.3, 0.6})
      for (double tauSlant : {0.5, 3.0, 20.0, 200.0}) {
        const double direct = std::exp(-tauSlant);
        EXPECT_NEAR(shared::cloudSlabTransmission(tauSlant, mu0, g),
                    direct + floorCorrection(mu0) * (baseFlux(mu0, mu0 * tauSlant, g) - direct), 1e-9)
            << mu0 << " " << g << " " << tauSlant;
      }
}

TEST(CloudDeckTransmission, MatchesTheSlabMonteCarlo) {
  // The diffuse flux out of the base (photons of scattering orders >= 1, 100000 per case, the default
  // phase, g its mean cosine) against cloudSlabTransmission less the direct beam. Measured
  // (200000 photons, depth 1-40, mu0 0.087-1): the Eddington form alone 15-22 % too large at mu0 = 0.087,
  // 9-13 % at 0.15; with the corrections 0.978-1.077, and 0.978-1.037 for mu0 <= 0.5. The standard error
  // here is 0.3-1.3 %; measured here 0.986-1.047 (the Eddington form 0.992-1.202).
  const CloudLightingSettings l;  // the phase SlabMonteCarlo samples
  const double g = shared::cloudPhaseMeanCosine(l.gForward, l.gBack, l.backWeight, l.alpha);
  for (double tau : {2.0, 10.0, 20.0})
    for (double mu0 : {0.087, 0.3, 1.0}) {
      SlabMonteCarlo slab(tau, mu0, uint64_t(31 + 1000 * tau + 100 * mu0));
      const SlabEstimate mc = slab.photonsThroughBase(100000, 1, 1).flux;
      const double direct = std::exp(-tau / mu0);
      const double model = shared::cloudSlabTransmission(tau / mu0, mu0, g) - direct;
      const double eddington = std::min(shared::cloudEddingtonTransmission(mu0, tau, g), 1.0) - direct;
      std::printf(
          "depth %4.1f mu0 %.3f: Monte Carlo %.4f +- %.4f, Eddington / MC %.3f, cloudSlabTransmission / MC %.3f\n", tau,
          mu0, mc.mean, mc.standardError, eddington / mc.mean, model / mc.mean);
      EXPECT_NEAR(model / mc.mean, 1.0, mu0 < 0.5 ? 0.05 : 0.06) << tau << " " << mu0;
      // The check can fail: the uncorrected form misses a low sun by more than the tolerance.
      if (mu0 < 0.1) {
        EXPECT_GT(eddington / mc.mean, 1.12) << tau;
      }
    }
}

TEST(CloudDeckTransmission, FallsAsOneOverDepthAndStaysInZeroToOne) {
  EXPECT_DOUBLE_EQ(shared::cloudSlabTransmission(0.0, 0.7, 0.47), 1.0);
  // A thick slab: T tau -> c (2/3 + mu0) / ((1 - g) mu0) with the floor's correction c, so doubling the
  // depth halves T. (At tau 1e4 the 4/3 in the denominator is 0.04 % of it.)
  const double t1 = shared::cloudSlabTransmission(1e4, 0.7, 0.47), t2 = shared::cloudSlabTransmission(2e4, 0.7, 0.47);
  EXPECT_NEAR(t2 / t1, 0.5, 5e-4);
  EXPECT_NEAR(t1 * 1e4, floorCorrection(0.7) * (2.0 / 3.0 + 0.7) / (0.53 * 0.7), 5e-4 * t1 * 1e4);
  // Any sun (at and below the horizon too), depth and phase: finite, in [0, 1], not rising with depth.
  for (double mu0 : {-0.3, 0.0, 1e-6, 0.05, 0.5, 1.0})
    for (double g : {-0.5, 0.0, 0.47, 0.85, 0.99}) {
      double last = 1.0;
      for (double tau : {0.0, 1e-8, 0.1, 1.0, 10.0, 1e2, 1e4}) {
        const double t = shared::cloudSlabTransmission(tau, mu0, g);
        EXPECT_TRUE(std::isfinite(t)) << mu0 << " " << g << " " << tau;
        EXPECT_GE(t, 0.0);
        EXPECT_LE(t, 1.0);
        EXPECT_LE(t, last + 1e-12) << mu0 << " " << g << " " << tau;
        last = t;
      }
    }
}

TEST(CloudDeckTransmission, OctaveThroughOthersOnlyAddsTheDecksDiffuseLight) {
  for (bool scatteredOnly : {false, true})
    for (double s : {0.1, 0.445, 0.9})
      for (double tauOwn : {0.0, 0.5, 5.0}) {
        // Without another layer on the way: the octave's own attenuation, exactly.
        EXPECT_EQ(shared::cloudOctaveTransmittanceThroughOthers(
                      s, tauOwn, 0.0, shared::cloudDeckDiffuseLight(0.0, 0.6, 0.47), 0.5, scatteredOnly),
                  shared::cloudOctaveTransmittance(s, tauOwn, scatteredOnly));
        for (double tauOther : {0.1, 2.0, 30.0, 1e4}) {
          const double t = shared::cloudOctaveTransmittanceThroughOthers(
              s, tauOwn, tauOther, shared::cloudDeckDiffuseLight(tauOther, 0.6, 0.47), 0.5, scatteredOnly);
          // Never below the octave through both (the deck only adds), never above 1, never negative.
          EXPECT_GE(t, shared::cloudOctaveTransmittance(s, tauOwn + tauOther, scatteredOnly) - 1e-15);
          EXPECT_LE(t, 1.0);
          EXPECT_GE(t, 0.0);
        }
      }
  // A thick deck: the octave's exponential is gone, its share of 2 mu0 T is left, attenuated by the own layer.
  const double mu0 = 0.6, g = 0.47, share = 0.5, tauOther = 50.0, tauOwn = 1.0, s = 0.445;
  const double deck = shared::cloudDeckDiffuseLight(tauOther, mu0, g);
  EXPECT_DOUBLE_EQ(deck, 2.0 * mu0 * shared::cloudSlabTransmission(tauOther, mu0, g));
  EXPECT_NEAR(shared::cloudOctaveTransmittanceThroughOthers(s, tauOwn, tauOther, deck, share, false),
              share * 2.0 * mu0 * shared::cloudSlabTransmission(tauOther, mu0, g) * std::exp(-s * tauOwn), 1e-12);
  // The octaves' shares sum to 1: together they carry 2 mu0 T, the light a sample scatters from the
  // deck's base radiance T mu0 E / pi over the upper hemisphere, (1/4pi) 2pi T mu0 E / pi.
  double sum = 0.0;
  for (double part : {0.6, 0.4})
    sum += shared::cloudOctaveTransmittanceThroughOthers(1.0, 0.0, tauOther, deck, part, false);
  EXPECT_NEAR(sum, 2.0 * mu0 * shared::cloudSlabTransmission(tauOther, mu0, g), 1e-12);
}

}  // namespace
}  // namespace firmament
