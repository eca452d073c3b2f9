// The diffusion floor (common/cloud_lighting.glsl cloudEddingtonSlabSource with cloudEscapeCorrection,
// cloudBaseLimbFactor at a base, cloudFloorLowSunFactor) against Monte Carlos of the case it is derived
// for (clouds/slab_monte_carlo.h): a homogeneous, conservatively scattering, plane-parallel slab lit by
// the sun, with the default dual Henyey-Greenstein phase, black below, no diffuse light from above. The
// Monte Carlos are exact up to their noise (a standard error of 0.3 to 2.9 %, bounded per check), so these
// are the floor's own errors: where the two-stream solution holds (the bulk of a thick slab, and the
// radiance leaving its base except at grazing exits) and what its two corrections take out. The wider
// sweeps those corrections were fitted to: `build/eval/micro/bench_floor_slab`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "clouds/slab_monte_carlo.h"
#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(CloudFloorAgainstMonteCarlo, HoldsInsideAThickSlab) {
  // Optical thickness 20, half-way down and three quarters down, light scattered up, sideways and down:
  // measured 0.970 to 1.030 (20000 paths per point, standard error 1.2 to 2.9 %; printed). Near the top
  // the octaves carry the light (the floor is 5 to 40 % low there at a high sun), and near the base the
  // light leaving it is checked below.
  const double thickness = 20.0;
  for (double mu0 : {0.5, 1.0}) {
    SlabMonteCarlo slab(thickness, mu0, uint64_t(100 * mu0));
    for (double depth : {0.5, 0.75})
      for (double muDown : {1.0, 0.0, -1.0}) {
        const SlabEstimate mc = slab.source(depth * thickness, slabDirection(muDown), 20000);
        const double truth = mc.mean, se = mc.standardError;
        const double floor = slabFloorSource(mu0, depth * thickness, thickness, muDown);
        std::printf("inside mu0 %.2f depth %.2f muDown %+.0f: floor / Monte Carlo %.3f (standard error %.3f)\n", mu0,
                    depth, muDown, floor / truth, se / truth);
        EXPECT_LT(se, 0.035 * truth);
        EXPECT_NEAR(floor / truth, 1.0, 0.07) << "mu0 " << mu0 << " depth " << depth << " muDown " << muDown;
      }
  }
}

TEST(CloudFloorAgainstMonteCarlo, BaseLimbDarkeningCorrectsGrazingExits) {
  // The radiance (orders >= 2) leaving the base of a slab of optical thickness 10, the sun 50 deg from
  // the zenith (the bench's overcast). Measured (printed; standard error 1.2 to 2.1 %): without the limb
  // darkening 0.992, 1.010, 1.039, 1.224, 1.260 at mu = 1, 0.5, 0.25, 0.1, 0.05; with it 0.984 to 1.042.
  const double thickness = 10.0, mu0 = std::cos(50.0 * kPi / 180.0);
  SlabMonteCarlo slab(thickness, mu0, 11);
  for (double muDown : {1.0, 0.5, 0.25, 0.1, 0.05}) {
    const SlabEstimate mc = slab.baseRadiance(slabDirection(muDown), 80000);
    const double truth = mc.mean, se = mc.standardError;
    EXPECT_LT(se, 0.025 * truth);
    const double plain = slabFloorBaseRadiance(mu0, thickness, muDown, false),
                 limb = slabFloorBaseRadiance(mu0, thickness, muDown, true);
    std::printf("base muDown %.2f: floor / Monte Carlo %.3f, with the limb darkening %.3f (standard error %.3f)\n",
                muDown, plain / truth, limb / truth, se / truth);
    EXPECT_NEAR(limb / truth, 1.0, 0.07) << "muDown " << muDown;
    if (muDown >= 0.5) {
      EXPECT_NEAR(plain / truth, 1.0, 0.05) << "muDown " << muDown;
    }
    if (muDown <= 0.05) {
      EXPECT_GT(plain / truth, 1.15) << "muDown " << muDown;  // what the factor corrects
    }
  }
}

TEST(CloudFloorAgainstMonteCarlo, LowSunFactorCorrectsTheGrazingEntry) {
  // Optical thickness 10. Measured (printed; 300 000 photons, standard error <= 0.6 %): the floor's flux
  // out of the base / the photons' is 1.097 with the sun 85 deg from the zenith, 1.061 at mu0 0.15, 1.001
  // overhead; with cloudFloorLowSunFactor 0.999 to 1.004. (The fit's sweep, thickness 10, 20 and 40, mu0
  // 0.087 to 1, binned by exit angle: `bench_floor_slab`.)
  const double thickness = 10.0;
  for (double mu0 : {std::cos(85.0 * kPi / 180.0), 0.15, 1.0}) {
    SlabMonteCarlo slab(thickness, mu0, uint64_t(1000 * mu0));
    const SlabEstimate mc = slab.photonsThroughBase(300000, 1).flux;
    const double truth = mc.mean, se = mc.standardError;
    EXPECT_LT(se, 0.01 * truth);
    const double plain = slabFloorBaseFlux(thickness, mu0) / truth,
                 corrected = plain * shared::cloudFloorLowSunFactor(mu0);
    std::printf(
        "mu0 %.3f: the floor's flux out of the base / Monte Carlo %.3f, with the low-sun factor %.3f (standard error "
        "%.3f)\n",
        mu0, plain, corrected, se / truth);
    EXPECT_NEAR(corrected, 1.0, 0.03) << "mu0 " << mu0;
    if (mu0 < 0.1) {
      EXPECT_GT(plain, 1.06) << "mu0 " << mu0;  // what the factor corrects
    }
  }
  // 1 - 0.178 e^(-mu0 / 0.125): within (0.82, 1], rising with mu0, ~1 for a high sun.
  double previous = 0.0;
  for (double m : {0.0, 0.05, 0.087, 0.2, 0.5, 1.0}) {
    const double f = shared::cloudFloorLowSunFactor(m);
    EXPECT_GT(f, previous);
    EXPECT_GE(f, 0.82);
    EXPECT_LE(f, 1.0);
    previous = f;
  }
  EXPECT_GT(shared::cloudFloorLowSunFactor(0.64), 0.998);
}

TEST(CloudFloorAgainstMonteCarlo, LimbDarkeningIsBoundedAndOnlyAtTheBase) {
  for (double mu : {1e-6, 0.01, 0.1, 0.5, 1.0})
    for (double tau : {0.0, 1e-6, 1.0, 1e4}) {
      const double f = shared::cloudBaseLimbFactor(mu, tau, std::exp(-tau / mu), 1.0);
      EXPECT_TRUE(std::isfinite(f));
      EXPECT_GE(f, 0.4);  // at most beta = 0.6 taken away
      EXPECT_LE(f, 1.0);
      EXPECT_EQ(shared::cloudBaseLimbFactor(-mu, tau, std::exp(-tau / mu), 1.0), 1.0);  // light scattered upwards
      EXPECT_EQ(shared::cloudBaseLimbFactor(mu, tau, std::exp(-tau / mu), 0.0), 1.0);   // strength 0: off
    }
  // Seen through a cloud's side (the way to the viewer much longer than the slant way to the base), the
  // source keeps nearly all of its value.
  EXPECT_GT(shared::cloudBaseLimbFactor(0.1, 0.01, std::exp(-30.0), 1.0), 0.999);
  EXPECT_LT(shared::cloudBaseLimbFactor(0.1, 0.01, std::exp(-0.1), 1.0), 0.85);
}

// The same medium cut to a vertical cylinder: a finite cloud loses diffuse light through its
// sides, which the column-wise floor (the slab's source at the column's depths) does not see. Thickness
// 20, sun overhead, the source of orders >= 2 at mid-depth on the axis, scattered down: bench_floor_slab
// part 4 measured 0.37 of the slab's at R/H = 0.5, 0.76 at 1, 1.03 at 2 (standard errors 1.5-3 %).
TEST(CloudFloorAgainstMonteCarlo, FiniteCloudLosesLightThroughItsSides) {
  const double thickness = 20.0;
  const int paths = 6000;
  const SlabDirection down = slabDirection(1.0, 90.0);
  auto axisSource = [&](double radius, double mu0, uint64_t seed) {
    SlabMonteCarlo cloud(thickness, mu0, seed, radius);
    return cloud.source(SlabPoint{0.0, 0.0, 0.5 * thickness}, down, paths);
  };
  // A radius far beyond any path's reach is the slab, path for path (same seed, same draws).
  SlabMonteCarlo slab(thickness, 1.0, 5);
  const SlabEstimate slabSource = slab.source(0.5 * thickness, down, paths);
  EXPECT_DOUBLE_EQ(axisSource(1e9, 1.0, 5).mean, slabSource.mean);
  const SlabEstimate narrow = axisSource(0.5 * thickness, 1.0, 6), square = axisSource(thickness, 1.0, 7),
                     wide = axisSource(4.0 * thickness, 1.0, 8);
  std::printf("axis source / slab's: R/H 0.5 %.3f, 1 %.3f, 4 %.3f (standard errors %.3f %.3f %.3f)\n",
              narrow.mean / slabSource.mean, square.mean / slabSource.mean, wide.mean / slabSource.mean,
              narrow.standardError / narrow.mean, square.standardError / square.mean, wide.standardError / wide.mean);
  EXPECT_LT(narrow.mean, 0.5 * slabSource.mean);
  EXPECT_GT(narrow.mean, 0.2 * slabSource.mean);
  EXPECT_LT(square.mean, 0.9 * slabSource.mean);
  EXPECT_GT(square.mean, 0.6 * slabSource.mean);
  EXPECT_NEAR(wide.mean / slabSource.mean, 1.0, 0.08);
  // A low sun enters through the sunlit side (x < 0): more light there than on the shadowed side.
  SlabMonteCarlo lowSun(thickness, 0.64, 9, thickness);
  const SlabEstimate lit =
      lowSun.source(SlabPoint{-0.75 * thickness, 0.0, 0.5 * thickness}, slabDirection(0.0, 90.0), paths);
  const SlabEstimate shaded =
      lowSun.source(SlabPoint{0.75 * thickness, 0.0, 0.5 * thickness}, slabDirection(0.0, 90.0), paths);
  std::printf("R/H 1, mu0 0.64, x/R -0.75 vs +0.75: %.4f vs %.4f\n", lit.mean, shaded.mean);
  EXPECT_GT(lit.mean, 2.0 * shaded.mean);
}

}  // namespace
}  // namespace firmament
