// The ray cast against closed forms (a flat field is a sphere, a tilted plane, a cliff within one
// cell, walls at the grid's edge, grazing rays, rays from under, on and far above the terrain, rays
// that miss), the pyramid walk against the cell-by-cell walk and against an independent fine march,
// and no NaN or Inf anywhere.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "common/geometry.glsl"
#include "terrain/procedural_terrain.h"
#include "terrain/terrain_intersection.h"
#include "tests/terrain/terrain_test_support.h"

namespace firmament::terrain {
namespace {
using test::kR;
using test::makeField;

glm::dvec3 up(double altitude) { return {0.0, 0.0, kR + altitude}; }
glm::dvec3 direction(double elevationDeg, double azimuthDeg) {
  const double e = elevationDeg * 3.14159265358979323846 / 180.0, a = azimuthDeg * 3.14159265358979323846 / 180.0;
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

// The near root of the ray against the sphere of radius R + h, in closed form (geometry.glsl).
double sphereHit(const glm::dvec3& o, const glm::dvec3& d, double h) {
  double r, mu, t0, t1;
  shared::rayRadiusAndCosine(o, d, r, mu);
  if (!shared::raySphereRoots(r, mu, kR + h, t0, t1)) return -1.0;
  return t0 >= 0.0 ? t0 : (t1 >= 0.0 ? 0.0 : -1.0);
}

void expectFiniteHit(const TerrainHit& hit) {
  ASSERT_TRUE(std::isfinite(hit.t));
  for (int c = 0; c < 3; ++c) {
    ASSERT_TRUE(std::isfinite(hit.position[c]));
    ASSERT_TRUE(std::isfinite(hit.normal[c]));
  }
  ASSERT_NEAR(glm::length(hit.normal), 1.0, 1e-9);
  ASSERT_TRUE(std::isfinite(hit.height));
}

TEST(TerrainIntersection, FlatFieldIsTheSphereOfRadiusRPlusH) {
  const double h = 523.25;
  const HeightField f = makeField(
      129, 20000.0, [&](double, double) { return h; }, h);
  const TerrainIntersector cast(f, kR);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> elevation(-89.9, -0.01), azimuth(0.0, 360.0);
  int onGrid = 0, outside = 0;
  for (double altitude : {h + 2.0, h + 800.0, 30000.0, 1.0e7}) {
    for (int k = 0; k < 300; ++k) {
      const glm::dvec3 o = up(altitude), d = direction(elevation(rng), azimuth(rng));
      const double expected = sphereHit(o, d, h);
      const TerrainHit hit = cast.intersect({o, d});
      ASSERT_EQ(hit.hit, expected >= 0.0);
      if (!hit.hit) continue;
      expectFiniteHit(hit);
      // 30 halvings of a cell's span leave < 1e-6 m; the closed form itself is good to ~1e-9 relative.
      EXPECT_NEAR(hit.t, expected, 1e-6 + 1e-9 * expected) << "altitude " << altitude;
      EXPECT_NEAR(glm::length(hit.position) - kR, h, 1e-5);
      EXPECT_LT(glm::length(hit.normal - glm::normalize(hit.position)), 1e-6);
      (hit.surface == TerrainSurface::Field ? onGrid : outside) += 1;
    }
  }
  EXPECT_GT(onGrid, 300);
  EXPECT_GT(outside, 100);
}

// h = h0 + s x: bilinear is exact for a plane. A vertical ray down through a plane point meets the
// surface at height h(x, y) exactly; its normal is the formula's, and near the location (−s, 0, 1).
TEST(TerrainIntersection, TiltedPlaneIsHitAtItsHeightWithItsNormal) {
  const double s = 0.7;  // 35°
  const HeightField f = makeField(65, 4000.0, [&](double x, double) { return 1000.0 + s * x; });
  const TerrainIntersector cast(f, kR);
  for (glm::dvec2 q : {glm::dvec2(0, 0), glm::dvec2(1234.5, -321.0), glm::dvec2(-3999.0, 3999.0)}) {
    const glm::dvec3 dir = glm::normalize(glm::dvec3(q.x, q.y, kR));
    for (double above : {0.5, 100.0, 5.0e6}) {
      const double hq = 1000.0 + s * q.x;
      const glm::dvec3 o = (kR + hq + above) * dir;
      const TerrainHit hit = cast.intersect({o, -dir});
      ASSERT_TRUE(hit.hit);
      expectFiniteHit(hit);
      EXPECT_NEAR(hit.t, above, 1e-6 + 1e-12 * above) << q.x << ", " << q.y;
      EXPECT_NEAR(hit.height, hq, 1e-4);
      EXPECT_NEAR(hit.plane.x, q.x, 1e-6);
    }
  }
  const TerrainHit centre = cast.intersect({up(3000.0), {0.0, 0.0, -1.0}});
  // A plane metre at height h is (R + h) / R metres of ground, so the slope there is s R / (R + h).
  EXPECT_LT(glm::length(centre.normal - glm::normalize(glm::dvec3(-s * kR / (kR + 1000.0), 0.0, 1.0))), 1e-6);
}

// A cliff within one cell: 0 m west of x = 0, 400 m east of x = 1 m (bilinear across the 1 m cell:
// 89.86°). A level ray at altitude a from the west meets the cliff face where its altitude equals the
// ramp, solved here by bisection on the closed forms.
TEST(TerrainIntersection, CliffWithinOneCellIsHitOnItsFace) {
  HeightField f(3, 2, -1.0, -50.0, 1.0, 100.0);
  f.at(0, 0) = f.at(0, 1) = 0.0f;
  f.at(1, 0) = f.at(1, 1) = 0.0f;
  f.at(2, 0) = f.at(2, 1) = 400.0f;
  const TerrainIntersector cast(f, kR);
  for (double a : {1.0, 150.0, 399.0}) {
    const glm::dvec3 o(-1.0 * (kR + a) / kR, 0.0, kR + a);  // over the grid's west edge, altitude ~a
    const glm::dvec3 d(1.0, 0.0, 0.0);
    const TerrainHit hit = cast.intersect({o, d});
    ASSERT_TRUE(hit.hit) << a;
    expectFiniteHit(hit);
    auto gap = [&](double t) {
      const glm::dvec3 p = o + t * d;
      const double x = kR * p.x / p.z;
      const double ramp = std::clamp(x, 0.0, 1.0) * 400.0;
      return (glm::length(p) - kR) - ramp;
    };
    double lo = 0.0, hi = 3.0;
    for (int k = 0; k < 200; ++k) (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
    EXPECT_NEAR(hit.t, hi, 1e-6) << a;
    EXPECT_GT(std::fabs(hit.normal.x), 0.99) << "a face, not the top";
    EXPECT_LT(hit.normal.x, 0.0);
  }
}

TEST(TerrainIntersection, WallsJoinTheGridAndTheOutsideSphere) {
  // A 100 m plateau on a sphere at 0 m: a level ray at 50 m from the west hits the plateau's west wall.
  const HeightField plateau = makeField(
      33, 1000.0, [](double, double) { return 100.0; }, 0.0);
  const TerrainIntersector cast(plateau, kR);
  const glm::dvec3 o = up(50.0) + glm::dvec3(-3000.0, 0.0, 0.0);
  const TerrainHit hit = cast.intersect({o, {1.0, 0.0, 0.0}});
  ASSERT_TRUE(hit.hit);
  expectFiniteHit(hit);
  EXPECT_EQ(hit.surface, TerrainSurface::Wall);
  EXPECT_NEAR(hit.plane.x, -1000.0, 1e-3);
  EXPECT_LT(hit.normal.x, -0.99);
  // A basin: the grid at 0 m inside an outside sphere at 100 m: leaving the grid eastwards at 50 m.
  const HeightField basin = makeField(
      33, 1000.0, [](double, double) { return 0.0; }, 100.0);
  const TerrainIntersector basinCast(basin, kR);
  const TerrainHit out = basinCast.intersect({up(50.0), {1.0, 0.0, 0.0}});
  ASSERT_TRUE(out.hit);
  EXPECT_EQ(out.surface, TerrainSurface::Wall);
  EXPECT_NEAR(out.plane.x, 1000.0, 1e-3);
  EXPECT_LT(out.normal.x, -0.99);  // the wall faces back into the basin
  // No outside surface: a ray leaving the grid misses.
  const HeightField island = makeField(33, 1000.0, [](double, double) { return 0.0; });
  EXPECT_FALSE(TerrainIntersector(island, kR).intersect({up(50.0), {1.0, 0.0, 0.0}}).hit);
}

TEST(TerrainIntersection, GrazingRaysTouchOrMissByTheirClearance) {
  // A flat field at 300 m: from 2 km, a ray whose closest approach to the centre is R + 300 ± 1 mm.
  const double h = 300.0;
  const HeightField f = makeField(257, 200000.0, [&](double, double) { return h; });
  const TerrainIntersector cast(f, kR);
  const double r = kR + 2000.0;
  for (double clearance : {-1e-3, 1e-3}) {
    const double p = kR + h + clearance;  // impact parameter
    const double sinZenith = p / r;
    const glm::dvec3 d(std::sin(std::asin(sinZenith)), 0.0, -std::cos(std::asin(sinZenith)));
    const TerrainHit hit = cast.intersect({up(2000.0), d});
    EXPECT_EQ(hit.hit, clearance < 0.0) << clearance;
    if (hit.hit) {
      expectFiniteHit(hit);
      EXPECT_NEAR(hit.t, sphereHit(up(2000.0), d, h), 0.5);  // ill-conditioned at tangency: 1 mm → ±0.4 m in t
    }
  }
}

TEST(TerrainIntersection, RaysFromUnderAndFromFarAboveAndRaysThatMiss) {
  const HeightField f = ProceduralTerrainField([] {
                          ProceduralTerrain p;
                          p.style = TerrainStyle::Alpine;
                          p.baseHeight = 1500.0;
                          return p;
                        }())
                            .tile(TileRegion::centred(0, 0, 10000.0, 257));
  const TerrainIntersector cast(f, kR);
  const double ground = f.sample(0.0, 0.0);
  // Under the surface, and inside the planet: the hit is the start.
  for (double below : {0.01, 50.0, 3.0e6}) {
    const TerrainHit hit = cast.intersect({up(ground - below), direction(10.0, 45.0)});
    ASSERT_TRUE(hit.hit);
    EXPECT_TRUE(hit.startedInside);
    EXPECT_EQ(hit.t, 0.0);
    expectFiniteHit(hit);
  }
  // From 1e8 m straight down onto the location.
  const TerrainHit far = cast.intersect({up(1.0e8), {0.0, 0.0, -1.0}});
  ASSERT_TRUE(far.hit);
  EXPECT_NEAR(far.t, 1.0e8 - ground, 1e-4);
  // Misses: up, level from space, and down from beside the grid with nothing outside it.
  EXPECT_FALSE(cast.intersect({up(ground + 2.0), direction(30.0, 10.0)}).hit);
  EXPECT_FALSE(cast.intersect({up(100000.0), direction(0.0, 10.0)}).hit);
  EXPECT_FALSE(cast.intersect({up(5000.0) + glm::dvec3(20000.0, 0.0, 0.0), {0.0, 0.0, -1.0}}).hit);
  // tMax before the ground.
  EXPECT_FALSE(cast.intersect({up(1.0e8), {0.0, 0.0, -1.0}, 0.0, 1.0e7}).hit);
}

// An independent reference: march t in steps of a tenth of a cell through the shell of the field's
// heights with HeightField::sample, then bisect the first sign change.
TerrainHit fineMarch(const HeightField& f, const TerrainRay& ray, double step) {
  TerrainHit hit;
  const glm::dvec3 d = glm::normalize(ray.direction);
  auto gap = [&](double t) {
    const glm::dvec3 p = ray.origin + t * d;
    const double x = kR * p.x / p.z, y = kR * p.y / p.z;
    const double h = p.z > 0.0 && f.contains(x, y) ? f.sample(x, y) : f.outsideHeight;
    if (std::isnan(h)) return 1e30;
    return glm::length(p) - kR - h;
  };
  double r, mu, t0, t1;
  shared::rayRadiusAndCosine(ray.origin, d, r, mu);
  if (!shared::raySphereRoots(r, mu, kR + f.maxHeight(), t0, t1) || t1 < 0.0) return hit;
  double t = std::max(0.0, t0), previous = t;
  if (gap(t) <= 0.0) {
    hit.hit = true;
    hit.t = t;
    return hit;
  }
  for (; t <= t1 + step; t += step) {
    if (gap(t) <= 0.0) {
      double lo = previous, hi = t;
      for (int k = 0; k < 60; ++k) (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
      hit.hit = true;
      hit.t = hi;
      return hit;
    }
    previous = t;
  }
  return hit;
}

TEST(TerrainIntersection, PyramidWalkFindsTheHitsOfTheCellWalkAndOfAFineMarch) {
  for (TerrainStyle style : {TerrainStyle::Alpine, TerrainStyle::Canyon}) {
    ProceduralTerrain p;
    p.style = style;
    p.baseHeight = 1000.0;
    const HeightField f = ProceduralTerrainField(p).tile(TileRegion::centred(0, 0, 6000.0, 129));  // 47 m cells
    const TerrainIntersector cast(f, kR);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> elevation(-40.0, 5.0), azimuth(0.0, 360.0), offset(-2500.0, 2500.0);
    int hits = 0, grazes = 0;
    long nodes = 0, nodesFlat = 0, cells = 0, cellsFlat = 0;
    for (int k = 0; k < 400; ++k) {
      const double x = offset(rng), y = offset(rng);
      const double ground = f.sample(x, y);
      const double above = k % 4 == 0 ? 2.0 : k % 4 == 1 ? 50.0 : k % 4 == 2 ? 600.0 : 3000.0;
      const glm::dvec3 o = (kR + ground + above) * glm::normalize(glm::dvec3(x, y, kR));
      const TerrainRay ray{o, direction(elevation(rng), azimuth(rng))};
      const TerrainHit a = cast.intersect(ray), b = cast.intersectCellByCell(ray);
      nodes += a.nodesVisited;
      cells += a.cellsTested;
      cellsFlat += b.cellsTested;
      nodesFlat += b.nodesVisited;
      ASSERT_EQ(a.hit, b.hit) << "ray " << k;
      if (a.hit) {
        expectFiniteHit(a);
        EXPECT_NEAR(a.t, b.t, 1e-6 * (1.0 + a.t)) << "ray " << k;
        ++hits;
      }
      const TerrainHit m = fineMarch(f, ray, f.dx / 10.0);
      if (m.hit != a.hit || (a.hit && std::fabs(m.t - a.t) > 1e-3 * (1.0 + a.t))) {
        // Only a graze the march's step jumps over may differ: the ray's clearance there is tiny.
        ++grazes;
        const double t = a.hit ? a.t : m.t;
        const glm::dvec3 q = ray.origin + t * glm::normalize(ray.direction);
        const double x2 = kR * q.x / q.z, y2 = kR * q.y / q.z;
        EXPECT_LT(std::fabs(glm::length(q) - kR - f.sample(x2, y2)), 0.05) << "ray " << k;
      }
    }
    std::printf(
        "%s: %d of 400 rays hit; pyramid %.1f nodes and %.1f cells tested per ray, cell walk %.1f cells "
        "visited and %.1f tested; %d grazes differ from the fine march\n",
        styleParameters(style).name, hits, nodes / 400.0, cells / 400.0, nodesFlat / 400.0, cellsFlat / 400.0, grazes);
    EXPECT_GT(hits, 200);
    EXPECT_LE(grazes, 2);
    EXPECT_LE(cells, cellsFlat);  // the pyramid tests no cell the cell walk would not
  }
}

// Robustness over the cases the design names: cameras under, on and far above the terrain, the sun
// at grazing elevations (shadow rays from the surface), vertical cliffs (canyon risers).
TEST(TerrainIntersection, NoNaNOrInfForAnyCameraAndGrazingShadowRays) {
  ProceduralTerrain p;
  p.style = TerrainStyle::Canyon;
  p.verticalScale = 4.0;  // 2.4 km of terraces on 8 km: near-vertical risers
  p.baseHeight = 500.0;
  const HeightField f = ProceduralTerrainField(p).tile(TileRegion::centred(0, 0, 8000.0, 257));
  HeightField withOutside = f;
  withOutside.outsideHeight = 500.0;
  const TerrainIntersector cast(withOutside, kR);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), offset(-3900.0, 3900.0);
  int hits = 0;
  for (int k = 0; k < 3000; ++k) {
    const double x = offset(rng), y = offset(rng), ground = f.sample(x, y);
    const double altitude = std::array<double, 6>{-100.0, 0.0, 1e-3, 10.0, 2e4, 4e8}[size_t(k % 6)];
    const glm::dvec3 o = (kR + ground + altitude) * glm::normalize(glm::dvec3(x, y, kR));
    glm::dvec3 d(unit(rng), unit(rng), unit(rng));
    if (k % 3 == 0) d.z = 1e-4 * unit(rng);  // grazing
    if (glm::length(d) < 1e-6) d = {1.0, 0.0, 0.0};
    const TerrainHit hit = cast.intersect({o, d});
    if (hit.hit) {
      ++hits;
      expectFiniteHit(hit);
      // A shadow ray from just above the hit towards a sun 0.5° above the horizon.
      const glm::dvec3 start = hit.position + 0.01 * hit.normal;
      const TerrainHit shadow = cast.intersect({start, direction(0.5, double(k % 360))});
      if (shadow.hit) expectFiniteHit(shadow);
    }
  }
  EXPECT_GT(hits, 1000);
}

// A rising ray's plane point tends to R d / d.z, so a ray heading almost due west (d.y ~ 1e-9) never
// reaches the grid lines north of the camera's cell. A walk that read those lines' (negative)
// crossings as "now" stepped north across the grid without moving along the ray and hit a ridge
// 10 km away at t = 0 (single terrain pixels in the sky of the default scene). Ridge 3000 m high in
// the north, the camera at 1900 m over flat 1200 m ground, rays rising 5 to 30 degrees: no hit.
TEST(TerrainIntersection, RisingRayAlongAGridLineNeverReachesTheLinesBeyondItsAsymptote) {
  const HeightField f = makeField(1024, 15000.0, [](double, double y) { return y > 8000.0 ? 3000.0 : 1200.0; });
  const TerrainIntersector cast(f, kR);
  int rays = 0;
  for (double elevation = 5.0; elevation <= 30.0; elevation += 2.5)
    for (double tiny : {1e-12, 1e-9, 1e-7, -1e-9}) {
      glm::dvec3 d = direction(elevation, 270.0);
      d.y = tiny;
      const TerrainHit hit = cast.intersect({up(1900.0), glm::normalize(d)});
      EXPECT_FALSE(hit.hit) << "elevation " << elevation << " d.y " << tiny << ": t " << hit.t;
      ++rays;
    }
  // The same ray falling toward the ridge side still finds the flat ground where the sphere says.
  const glm::dvec3 down = glm::normalize(glm::dvec3(-1.0, 1e-9, -0.2));
  const TerrainHit hit = cast.intersect({up(1900.0), down});
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.t, sphereHit(up(1900.0), down, 1200.0), 1e-3);
  EXPECT_EQ(rays, 44);
}
}  // namespace
}  // namespace firmament::terrain
