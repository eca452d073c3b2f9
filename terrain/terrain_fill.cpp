#include "terrain/terrain_fill.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace firmament::terrain {

double fillFromFallback(HeightField& field, const std::function<double(double, double)>& fallback, double blend_m) {
  const int nx = field.nx, ny = field.ny;
  const size_t n = size_t(nx) * size_t(ny);
  constexpr float kFar = std::numeric_limits<float>::infinity();
  std::vector<float> distance(n, kFar);
  std::vector<int> nearest(n, -1);
  size_t valid = 0;
  for (size_t k = 0; k < n; ++k)
    if (!std::isnan(field.heights[k])) {
      distance[k] = 0.0f;
      nearest[k] = int(k);
      ++valid;
    }
  if (valid == n) return 1.0;
  const float ax = float(field.dx), ay = float(field.dy), diagonal = float(std::hypot(field.dx, field.dy));
  auto relax = [&](int i, int j, int di, int dj, float cost) {
    const int si = i + di, sj = j + dj;
    if (si < 0 || si >= nx || sj < 0 || sj >= ny) return;
    const size_t from = size_t(sj) * size_t(nx) + size_t(si), to = size_t(j) * size_t(nx) + size_t(i);
    if (distance[from] + cost < distance[to]) {
      distance[to] = distance[from] + cost;
      nearest[to] = nearest[from];
    }
  };
  if (valid > 0) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        relax(i, j, -1, 0, ax);
        relax(i, j, -1, -1, diagonal);
        relax(i, j, 0, -1, ay);
        relax(i, j, 1, -1, diagonal);
      }
    for (int j = ny - 1; j >= 0; --j)
      for (int i = nx - 1; i >= 0; --i) {
        relax(i, j, 1, 0, ax);
        relax(i, j, 1, 1, diagonal);
        relax(i, j, 0, 1, ay);
        relax(i, j, -1, 1, diagonal);
      }
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t k = size_t(j) * size_t(nx) + size_t(i);
      if (!std::isnan(field.heights[k])) continue;
      const double fb = fallback(field.xAt(i), field.yAt(j));
      if (nearest[k] < 0) {
        field.heights[k] = float(fb);
        continue;
      }
      double w = 1.0;
      if (blend_m > 0.0) {
        const double s = std::clamp(double(distance[k]) / blend_m, 0.0, 1.0);
        w = s * s * (3.0 - 2.0 * s);
      }
      const double edge = field.heights[size_t(nearest[k])];
      field.heights[k] = float(edge + (fb - edge) * w);
    }
  return double(valid) / double(n);
}

HeightField resampleField(const HeightField& source, const TileRegion& region, double marginX, double marginY) {
  HeightField out(region.nx, region.ny, region.x0, region.y0, region.dx, region.dy);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int j = 0; j < region.ny; ++j)
    for (int i = 0; i < region.nx; ++i) {
      const double x = out.xAt(i), y = out.yAt(j);
      if (x < source.x0 - marginX || x > source.xMax() + marginX || y < source.y0 - marginY ||
          y > source.yMax() + marginY) {
        out.at(i, j) = nan;
        continue;
      }
      out.at(i, j) =
          float(source.sample(std::clamp(x, source.x0, source.xMax()), std::clamp(y, source.y0, source.yMax())));
    }
  out.source = source.source;
  return out;
}

}  // namespace firmament::terrain
