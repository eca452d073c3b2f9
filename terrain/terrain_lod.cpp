#include "terrain/terrain_lod.h"

#include <algorithm>
#include <cmath>

namespace firmament::terrain {
namespace {

// Level k + 1 of level k: every other sample, [1 2 1] / 4 in x then y, indices clamped to level k.
HeightField coarser(const HeightField& f) {
  const int nx = (f.nx - 1 + 1) / 2 + 1, ny = (f.ny - 1 + 1) / 2 + 1;  // ceil((n - 1) / 2) + 1
  HeightField c(nx, ny, f.x0, f.y0, 2.0 * f.dx, 2.0 * f.dy);
  c.outsideHeight = f.outsideHeight;
  c.source = f.source;
  std::vector<float> rows(size_t(nx) * size_t(f.ny));  // filtered in x: nx × f.ny
  auto clampX = [&](int i) { return std::clamp(i, 0, f.nx - 1); };
  auto clampY = [&](int j) { return std::clamp(j, 0, f.ny - 1); };
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < nx; ++i)
      rows[size_t(j) * size_t(nx) + size_t(i)] =
          0.25f * f.at(clampX(2 * i - 1), j) + 0.5f * f.at(clampX(2 * i), j) + 0.25f * f.at(clampX(2 * i + 1), j);
  auto row = [&](int i, int j) { return rows[size_t(clampY(j)) * size_t(nx) + size_t(i)]; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      c.at(i, j) = 0.25f * row(i, 2 * j - 1) + 0.5f * row(i, 2 * j) + 0.25f * row(i, 2 * j + 1);
  return c;
}

}  // namespace

TerrainLod buildTerrainLod(const HeightField& field, int maxLevel) {
  TerrainLod lod;
  lod.levels.push_back(field);
  lod.levelBounds.emplace_back(field);
  const int top = lod.levelBounds[0].levels() - 1;
  for (int k = 1; k <= std::min(maxLevel, top); ++k) {
    lod.levels.push_back(coarser(lod.levels.back()));
    lod.levelBounds.emplace_back(lod.levels.back());
  }
  return lod;
}

double sampleTerrainLod(const TerrainLod& lod, double x, double y, double lambda) {
  const int last = int(lod.levels.size()) - 1;
  lambda = std::clamp(lambda, 0.0, double(last));
  const int k = std::min(int(std::floor(lambda)), last);
  const double f = lambda - k;
  auto at = [&](int level) {
    const HeightField& h = lod.levels[size_t(level)];
    const double gx = std::clamp((x - h.x0) / h.dx, 0.0, double(h.nx - 1));
    const double gy = std::clamp((y - h.y0) / h.dy, 0.0, double(h.ny - 1));
    const int i = std::min(int(gx), h.nx - 2), j = std::min(int(gy), h.ny - 2);
    const double fx = gx - i, fy = gy - j;
    const double s = h.at(i, j) + (h.at(i + 1, j) - h.at(i, j)) * fx;
    const double n = h.at(i, j + 1) + (h.at(i + 1, j + 1) - h.at(i, j + 1)) * fx;
    return s + (n - s) * fy;
  };
  const double a = at(k);
  return f > 0.0 && k < last ? a + (at(k + 1) - a) * f : a;
}

}  // namespace firmament::terrain
