// Level of detail (terrain/terrain_lod.h): the filtered levels keep a plane a plane (the tent filter
// reproduces linear functions), shrink a checkerboard's relief as a low-pass filter must, and their
// min/max bounds contain the blended surface at every fractional level (what keeps the GPU walk's
// skipping conservative).
#include <gtest/gtest.h>

#include <random>

#include "terrain/terrain_lod.h"
#include "tests/terrain/terrain_test_support.h"

namespace firmament::terrain {
namespace {

TEST(TerrainLod, LevelsReproduceAPlaneAwayFromTheEdges) {
  const HeightField field = test::makeField(257, 1280.0, [](double x, double y) { return 0.3 * x - 0.2 * y + 500.0; });
  const TerrainLod lod = buildTerrainLod(field, 8);
  ASSERT_EQ(lod.levels.size(), 9u);
  double worst = 0.0;
  for (double lambda : {0.0, 0.5, 1.0, 2.25, 3.5, 5.0}) {
    const double margin = 10.0 * (1 << (int(lambda) + 1)) * field.dx;
    for (double x = -1280.0 + margin; x <= 1280.0 - margin; x += 37.0)
      for (double y = -1280.0 + margin; y <= 1280.0 - margin; y += 41.0)
        worst = std::max(worst, std::abs(sampleTerrainLod(lod, x, y, lambda) - (0.3 * x - 0.2 * y + 500.0)));
  }
  EXPECT_LT(worst, 1e-3);  // float heights of up to ~900 m
}

TEST(TerrainLod, LevelOneRemovesTheFinestCheckerboard) {
  // +-100 m alternating per sample: the highest frequency the grid holds; [1 2 1] / 4 cancels it.
  const HeightField field = test::makeField(65, 640.0, [](double x, double y) {
    const int i = int(std::lround((x + 640.0) / 20.0)), j = int(std::lround((y + 640.0) / 20.0));
    return ((i + j) % 2 == 0 ? 100.0 : -100.0) + 1000.0;
  });
  const TerrainLod lod = buildTerrainLod(field, 3);
  const HeightField& one = lod.levels[1];
  for (int j = 1; j + 1 < one.ny; ++j)
    for (int i = 1; i + 1 < one.nx; ++i) EXPECT_NEAR(one.at(i, j), 1000.0, 1e-3) << i << " " << j;
}

TEST(TerrainLod, BoundsContainTheBlendedSurfaceAtEveryLevel) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  HeightField field = test::makeField(203, 2000.0, [&](double x, double y) {
    return 800.0 * std::sin(x / 300.0) * std::cos(y / 170.0) + 90.0 * noise(rng);
  });
  const TerrainLod lod = buildTerrainLod(field, 8);
  const int levels = int(lod.levels.size());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int outside = 0;
  for (int n = 0; n < 20000; ++n) {
    const double x = field.x0 + u(rng) * (field.nx - 1) * field.dx, y = field.y0 + u(rng) * (field.ny - 1) * field.dy;
    const double lambda = u(rng) * (levels - 1);
    const double h = sampleTerrainLod(lod, x, y, lambda);
    // The fine cell under the point, and for the two levels blended the node at every pyramid level.
    const int ci = std::min(int((x - field.x0) / field.dx), field.nx - 2);
    const int cj = std::min(int((y - field.y0) / field.dy), field.ny - 2);
    const int k0 = int(lambda), k1 = std::min(k0 + 1, levels - 1);
    for (int L = 0; L < lod.levelBounds[0].levels(); ++L) {
      double lo = 1e30, hi = -1e30;
      for (int k : {k0, k1}) {
        const int at = std::max(L, k);
        const MinMaxLevel& b = lod.levelBounds[size_t(k)].level(at - k);
        lo = std::min(lo, double(b.min(ci >> at, cj >> at)));
        hi = std::max(hi, double(b.max(ci >> at, cj >> at)));
      }
      outside += h < lo - 1e-3 || h > hi + 1e-3;
    }
  }
  EXPECT_EQ(outside, 0);
}

}  // namespace
}  // namespace firmament::terrain
