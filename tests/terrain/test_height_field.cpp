// The height field's sampling, gradient and normal against closed forms; the min/max pyramid's
// bounds; the plane ↔ geodetic frame against GeographicLib's geodesics.
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <random>

#include "common/terrain_geometry.glsl"
#include "terrain/min_max_pyramid.h"
#include "terrain/terrain_frame.h"
#include "tests/terrain/terrain_test_support.h"

namespace firmament::terrain {
namespace {
using test::kR;
using test::makeField;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

TEST(HeightField, BilinearReproducesSamplesAndLinearFields) {
  // h = 100 + 0.3 x − 0.2 y is linear, so bilinear interpolation is exact everywhere inside.
  const HeightField f = makeField(
      33, 500.0, [](double x, double y) { return 100.0 + 0.25 * x - 0.125 * y; }, -5.0);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-500.0, 500.0);
  for (int k = 0; k < 1000; ++k) {
    const double x = u(rng), y = u(rng);
    EXPECT_NEAR(f.sample(x, y), 100.0 + 0.25 * x - 0.125 * y, 1e-4);
    const glm::dvec2 g = f.gradient(x, y);
    EXPECT_NEAR(g.x, 0.25, 1e-6);
    EXPECT_NEAR(g.y, -0.125, 1e-6);
  }
  EXPECT_EQ(f.sample(f.xAt(3), f.yAt(7)), f.at(3, 7));
  EXPECT_EQ(f.sample(600.0, 0.0), -5.0);  // outside: the stated sphere
  EXPECT_EQ(f.sample(0.0, -501.0), -5.0);
}

// The normal formula of terrain_geometry.glsl against the cross product of the surface's tangents
// P(x, y) = (R + h) normalize(x, y, R), differentiated numerically.
TEST(HeightField, SurfaceNormalIsTheCrossProductOfTheSurfaceTangents) {
  const double s = 0.4, t = -0.7;
  auto h = [&](double x, double y) { return 800.0 + s * x + t * y; };
  auto P = [&](double x, double y) { return shared::terrainSurfacePoint({x, y}, h(x, y), kR); };
  for (glm::dvec2 q :
       {glm::dvec2(0, 0), glm::dvec2(3000, -2000), glm::dvec2(-90000, 40000), glm::dvec2(250000, 250000)}) {
    const double e = 0.5;
    const glm::dvec3 tx = (P(q.x + e, q.y) - P(q.x - e, q.y)) / (2 * e);
    const glm::dvec3 ty = (P(q.x, q.y + e) - P(q.x, q.y - e)) / (2 * e);
    const glm::dvec3 expected = glm::normalize(glm::cross(tx, ty));
    const glm::dvec3 n = shared::terrainSurfaceNormal(q, h(q.x, q.y), {s, t}, kR);
    EXPECT_LT(glm::length(n - expected), 1e-7) << q.x << ", " << q.y;
  }
  // At the location: the flat-ground normal normalize(−s, −t, 1).
  const glm::dvec3 n0 = shared::terrainSurfaceNormal({0, 0}, 0.0, {s, t}, kR);
  EXPECT_LT(glm::length(n0 - glm::normalize(glm::dvec3(-s, -t, 1.0))), 1e-12);
}

TEST(MinMaxPyramid, EveryTexelBoundsTheCellsBelowIt) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-300.0, 2500.0);
  HeightField f(45, 38, 0.0, 0.0, 10.0, 12.0);  // not a power of two, not square
  for (float& h : f.heights) h = float(u(rng));
  const MinMaxPyramid p(f);
  EXPECT_EQ(p.level(0).width, 44);
  EXPECT_EQ(p.level(0).height, 37);
  EXPECT_EQ(p.level(p.levels() - 1).width, 1);
  EXPECT_EQ(p.level(p.levels() - 1).height, 1);
  EXPECT_EQ(p.fieldMin(), float(f.minHeight()));
  EXPECT_EQ(p.fieldMax(), float(f.maxHeight()));
  for (int k = 0; k < p.levels(); ++k) {
    const MinMaxLevel& level = p.level(k);
    for (int j = 0; j < level.height; ++j)
      for (int i = 0; i < level.width; ++i) {
        float lo = 1e30f, hi = -1e30f;
        for (int cj = j << k; cj < std::min((j + 1) << k, f.ny - 1); ++cj)
          for (int ci = i << k; ci < std::min((i + 1) << k, f.nx - 1); ++ci)
            for (int c = 0; c < 4; ++c) {
              const float h = f.at(ci + (c & 1), cj + (c >> 1));
              lo = std::min(lo, h);
              hi = std::max(hi, h);
            }
        ASSERT_EQ(level.min(i, j), lo) << "level " << k << " texel " << i << ", " << j;
        ASSERT_EQ(level.max(i, j), hi) << "level " << k << " texel " << i << ", " << j;
      }
  }
}

// A plane point lies on the geodesic from the location along its azimuth, at distance R atan(ρ / R):
// checked with GeographicLib's Geodesic directly (not through the projection the frame uses).
TEST(TerrainFrame, PlanePointsAreAtTheirGeodesicDistanceAndAzimuth) {
  const auto location = astro::GeodeticLocation::fromDegrees(46.55, 7.98, 1200.0);
  const TerrainFrame frame(location, kR);
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  for (glm::dvec2 q :
       {glm::dvec2(1000, 0), glm::dvec2(0, -25000), glm::dvec2(70000, 70000), glm::dvec2(-300000, 120000)}) {
    const glm::dvec2 ll = frame.planeToGeodetic(q);
    double s12 = 0, azi1 = 0, azi2 = 0;
    g.Inverse(46.55, 7.98, ll.x / kDegree, ll.y / kDegree, s12, azi1, azi2);
    const double rho = std::hypot(q.x, q.y);
    EXPECT_NEAR(s12, kR * std::atan(rho / kR), 1e-6) << q.x << ", " << q.y;
    EXPECT_NEAR(std::remainder(azi1 - std::atan2(q.x, q.y) / kDegree, 360.0), 0.0, 1e-9);
    const glm::dvec2 back = frame.geodeticToPlane(ll);
    EXPECT_NEAR(back.x, q.x, 1e-6);
    EXPECT_NEAR(back.y, q.y, 1e-6);
  }
  const glm::dvec2 origin = frame.planeToGeodetic({0.0, 0.0});
  EXPECT_NEAR(origin.x, location.latitude, 1e-15);
  EXPECT_NEAR(origin.y, location.longitude, 1e-15);
  // The antipode is beyond the gnomonic plane.
  EXPECT_TRUE(std::isnan(frame.geodeticToPlane({-46.55 * kDegree, (7.98 - 180.0) * kDegree}).x));
}

}  // namespace
}  // namespace firmament::terrain
