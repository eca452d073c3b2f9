// The terrain's horizon map (terrain/horizon_map.h) and the share of the sky it leaves a surface
// (common/terrain_sky_visibility.glsl) against closed forms: a plain in front of a straight cliff, the
// bottom of a V-shaped valley, an open plain and a tilted plane.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/terrain_sky_visibility.glsl"
#include "terrain/horizon_map.h"
#include "tests/terrain/terrain_test_support.h"

namespace firmament::terrain {
namespace {

using test::kR;
constexpr double kPi = 3.14159265358979323846;

// The cosine-weighted visible share at (x, y, h0) for the normal n = (nx, ny, nz) in the local frame,
// from `azimuths` horizons as the GPU sums them: (2 / A) sum_k slice_k.
double visibleShare(const HeightField& f, double x, double y, double h0, glm::dvec3 n, int azimuths) {
  double sum = 0.0;
  for (int k = 0; k < azimuths; ++k) {
    const double phi = 2.0 * kPi * (k + 0.5) / azimuths;
    const double alpha = horizonElevation(f, kR, x, y, h0, phi, HorizonMapSettings{}.stepRatio);
    sum += shared::terrainSkySlice(alpha, n.x * std::cos(phi) + n.y * std::sin(phi), n.z);
  }
  return 2.0 * sum / azimuths;
}

// A horizontal point on a plain at distance d from the foot of a straight cliff whose top it sees at
// elevation alpha straight ahead: horizon atan(tan(alpha) cos(phi)) over the half turn facing the cliff,
// the plain's 0 over the other; V = 1/2 + (1/2pi) int_{-pi/2}^{pi/2} dphi / (1 + tan^2(alpha) cos^2(phi))
// = (1 + cos alpha) / 2. The field: 5 m spacing across the cliff (a one-cell ramp from 0 to 400 m, its
// top edge the silhouette), 250 m along it over 20 km. tan(alpha) = (400 - d^2 / 2R) / d (the planet's
// curvature). Measured (elevations 14-86 deg): within 0.0006 of it with 64 azimuths; with 16 (the
// default) within 0.0003 up to 63 deg, -0.0044 at 76 deg and -0.017 at 86 deg, where the horizon turns
// from 86 deg to 0 within a sector of the midpoint rule. Tolerances 0.001 (64) and 0.02 (16).
TEST(HorizonMap, PlainBeforeACliffSeesOnePlusCosineOverTwo) {
  HeightField f(801, 81, -2000.0, -10000.0, 5.0, 250.0);
  const double top = 500.0, height = 400.0;
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) f.at(i, j) = f.xAt(i) >= top ? float(height) : 0.0f;
  f.outsideHeight = 0.0;
  double worst16 = 0.0, worst64 = 0.0;
  for (double d : {30.0, 100.0, 200.0, 400.0, 800.0, 1600.0}) {
    const double alpha = std::atan((height - 0.5 * d * d / kR) / d);
    const double expected = 0.5 * (1.0 + std::cos(alpha));
    const double v16 = visibleShare(f, top - d, 0.0, 0.0, {0.0, 0.0, 1.0}, 16);
    const double v64 = visibleShare(f, top - d, 0.0, 0.0, {0.0, 0.0, 1.0}, 64);
    worst16 = std::max(worst16, std::abs(v16 - expected));
    worst64 = std::max(worst64, std::abs(v64 - expected));
    std::printf("d %6.0f m: alpha %.1f deg, V %.4f, 16 azimuths %+.4f, 64 %+.4f\n", d, alpha * 180.0 / kPi, expected,
                v16 - expected, v64 - expected);
    EXPECT_NEAR(v16, expected, 0.02) << "d " << d;
    EXPECT_NEAR(v64, expected, 0.001) << "d " << d;
  }
  std::printf("cliff: largest |V - (1 + cos a)/2| %.4f (16 azimuths), %.4f (64)\n", worst16, worst64);
}

// The bottom of a V-shaped valley with flanks rising at beta: horizon atan(tan(beta) |cos(phi)|) all
// round, V = (1/2pi) int dphi / (1 + tan^2(beta) cos^2(phi)) = cos beta. Measured (10-60 deg): largest
// difference 0.0002 (16 azimuths); tolerance 0.003.
TEST(HorizonMap, BottomOfAVValleySeesCosineOfTheFlankAngle) {
  double worst = 0.0;
  for (double degrees : {10.0, 25.0, 40.0, 60.0}) {
    const double beta = degrees * kPi / 180.0;
    const HeightField f = test::makeField(401, 4000.0, [&](double x, double) { return std::abs(x) * std::tan(beta); });
    const double v = visibleShare(f, 0.0, 0.0, 0.0, {0.0, 0.0, 1.0}, 16);
    worst = std::max(worst, std::abs(v - std::cos(beta)));
    EXPECT_NEAR(v, std::cos(beta), 0.003) << degrees << " deg";
  }
  std::printf("V valley: largest |V - cos b| %.4f\n", worst);
}

// Nothing above the horizon: an open plain sees the whole sky (V = 1 to rounding); a plane tilted by
// beta over a plain far below sees its own hemisphere down to the plain's horizon, more than the
// isotropic (1 + cos beta) / 2 of a horizon at 0 and at most 1; with the horizon at 0 all round (the
// slices alone) exactly (1 + cos beta) / 2 up to the midpoint rule (measured 2e-4 at 16 azimuths,
// tolerance 1e-3).
TEST(HorizonMap, OpenPlainSeesTheWholeSkyAndATiltedPlaneItsOwnHemisphere) {
  const HeightField plain = test::makeField(
      65, 3000.0, [](double, double) { return 500.0; }, 500.0);
  EXPECT_NEAR(visibleShare(plain, 0.0, 0.0, 500.0, {0.0, 0.0, 1.0}, 16), 1.0, 1e-12);
  for (double degrees : {15.0, 35.0, 60.0}) {
    const double beta = degrees * kPi / 180.0;
    const glm::dvec3 n(-std::sin(beta), 0.0, std::cos(beta));  // the plane rises eastwards
    double sum = 0.0;
    for (int k = 0; k < 16; ++k) {
      const double phi = 2.0 * kPi * (k + 0.5) / 16.0;
      sum += shared::terrainSkySlice(0.0, n.x * std::cos(phi) + n.y * std::sin(phi), n.z);
    }
    EXPECT_NEAR(2.0 * sum / 16.0, 0.5 * (1.0 + std::cos(beta)), 1e-3) << degrees << " deg";
    const HeightField tilted = test::makeField(
        201, 2000.0, [&](double x, double) { return 3000.0 + x * std::tan(beta); }, 0.0);
    const double v = visibleShare(tilted, 0.0, 0.0, 3000.0, n, 16);
    EXPECT_GE(v, 0.5 * (1.0 + std::cos(beta)) - 1e-3) << degrees << " deg";
    EXPECT_LE(v, 1.0 + 1e-3) << degrees << " deg";
  }
}

// The baked map holds horizonElevation at every texel; a field over maxTexels samples a side is strided,
// and marched on the strided samples.
TEST(HorizonMap, BakedTexelsAreTheMarchedHorizonsAndLargeFieldsAreStrided) {
  const HeightField f = test::makeField(
      65, 3000.0, [](double x, double y) { return 300.0 * std::sin(x / 700.0) * std::cos(y / 900.0); }, 0.0);
  HorizonMapSettings s;
  s.azimuths = 8;
  const HorizonMap map = bakeHorizonMap(f, kR, s);
  ASSERT_EQ(map.width, 65);
  ASSERT_EQ(map.height, 65);
  for (int j = 0; j < 65; j += 16)
    for (int i = 0; i < 65; i += 16)
      for (int k = 0; k < 8; ++k)
        EXPECT_EQ(map.at(i, j, k), float(horizonElevation(f, kR, f.xAt(i), f.yAt(j), f.at(i, j),
                                                          2.0 * kPi * (k + 0.5) / 8.0, s.stepRatio)));
  s.maxTexels = 17;
  const HorizonMap coarse = bakeHorizonMap(f, kR, s);
  EXPECT_EQ(coarse.stride, 4);
  EXPECT_EQ(coarse.width, 17);
  EXPECT_DOUBLE_EQ(coarse.dx, 4.0 * f.dx);
  // A strided map is the map of the strided samples (the march reads them).
  HeightField every4(17, 17, f.x0, f.y0, 4.0 * f.dx, 4.0 * f.dy);
  for (int j = 0; j < 17; ++j)
    for (int i = 0; i < 17; ++i) every4.at(i, j) = f.at(4 * i, 4 * j);
  every4.outsideHeight = f.outsideHeight;
  s.maxTexels = 257;
  EXPECT_EQ(bakeHorizonMap(every4, kR, s).elevation, coarse.elevation);
}

}  // namespace
}  // namespace firmament::terrain
