#include "terrain/horizon_map.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

namespace firmament::terrain {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The distance along (cx, cy) from (x, y) inside the grid's rectangle to its edge.
double distanceToEdge(const HeightField& f, double x, double y, double cx, double cy) {
  double s = 1e30;
  if (cx > 1e-12) s = std::min(s, (f.xMax() - x) / cx);
  if (cx < -1e-12) s = std::min(s, (f.x0 - x) / cx);
  if (cy > 1e-12) s = std::min(s, (f.yMax() - y) / cy);
  if (cy < -1e-12) s = std::min(s, (f.y0 - y) / cy);
  return std::max(s, 0.0);
}

// Bilinear inside the grid (the point is known to be in it, up to rounding: clamped).
double sampleInside(const HeightField& f, double x, double y) {
  const double u = std::clamp((x - f.x0) / f.dx, 0.0, double(f.nx - 1));
  const double v = std::clamp((y - f.y0) / f.dy, 0.0, double(f.ny - 1));
  const int i = std::min(int(u), f.nx - 2), j = std::min(int(v), f.ny - 2);
  const double a = u - i, b = v - j;
  const float* row0 = f.heights.data() + size_t(j) * size_t(f.nx) + size_t(i);
  const float* row1 = row0 + f.nx;
  return (1.0 - b) * ((1.0 - a) * row0[0] + a * row0[1]) + b * ((1.0 - a) * row1[0] + a * row1[1]);
}

}  // namespace

double horizonElevation(const HeightField& f, double R, double x, double y, double h0, double phi, double stepRatio,
                        double top) {
  const double cx = std::cos(phi), cy = std::sin(phi);
  const double edge = distanceToEdge(f, x, y, cx, cy);
  // The largest tan of the elevation: (h(s) - h0 - s^2 / 2R) / s over the marched distances.
  double best = -1e30, bestS = 0.0;
  auto at = [&](double s) {
    const double v = (sampleInside(f, x + s * cx, y + s * cy) - h0 - 0.5 * s * s / R) / s;
    if (v > best) best = v, bestS = s;
  };
  const double first = 0.5 * std::min(f.dx, f.dy);
  const double ratio = std::max(stepRatio, 1.0001);
  // No step past the one where even the field's highest sample would stand lower than the best so far
  // ((top - h0 - s^2 / 2R) / s falls with s).
  bool reachedEdge = true;
  for (double s = first; s < edge; s *= ratio) {
    if ((top - h0 - 0.5 * s * s / R) / s <= best) {
      reachedEdge = false;
      break;
    }
    at(s);
  }
  if (edge > 0.0 && reachedEdge) at(edge);
  // Refined around the highest step, over the steps on either side, twice (8 samples a side at
  // ratio^(1/8), then at ratio^(1/64)): a sharp crest between two steps is otherwise seen up to a step
  // further away (the tan of its elevation up to ratio - 1 low).
  thread_local double factorsRatio = 0.0;
  thread_local double factors[2][17];
  if (factorsRatio != ratio) {
    for (int level = 0; level < 2; ++level)
      for (int k = -8; k <= 8; ++k) factors[level][k + 8] = std::pow(ratio, k / (level == 0 ? 8.0 : 64.0));
    factorsRatio = ratio;
  }
  for (int level = 0; level < 2; ++level) {
    const double s0 = bestS;
    if (!(s0 > 0.0)) break;
    for (int k = 0; k < 17; ++k) {
      const double s = s0 * factors[level][k];
      if (k != 8 && s < edge) at(s);
    }
  }
  // Past the grid, the outside sphere at its height: -D / s - s / 2R (D = h0 - outside) is largest at
  // s = sqrt(2 R D) for D > 0 (the geometric horizon), else at the edge.
  if (f.hasOutside()) {
    const double d = h0 - f.outsideHeight;
    const double s = std::max(d > 0.0 ? std::sqrt(2.0 * R * d) : 0.0, std::max(edge, first));
    best = std::max(best, (-d - 0.5 * s * s / R) / s);
  }
  return best > -1e29 ? std::atan(best) : -0.5 * kPi;
}

double horizonElevation(const HeightField& f, double R, double x, double y, double h0, double phi, double stepRatio) {
  return horizonElevation(f, R, x, y, h0, phi, stepRatio, f.maxHeight());
}

HorizonMap bakeHorizonMap(const HeightField& f, double R, const HorizonMapSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  HorizonMap map;
  const int largest = std::max(f.nx, f.ny);
  const int maxTexels = std::max(settings.maxTexels, 2);
  map.stride = std::max(1, (largest - 1 + maxTexels - 2) / (maxTexels - 1));
  map.width = (f.nx - 1) / map.stride + 1;
  map.height = (f.ny - 1) / map.stride + 1;
  map.azimuths = std::max(settings.azimuths, 1);
  map.x0 = f.x0, map.y0 = f.y0;
  map.dx = f.dx * map.stride, map.dy = f.dy * map.stride;
  map.elevation.assign(size_t(map.width) * size_t(map.height) * size_t(map.azimuths), 0.0f);
  // The march reads the texels' own samples (every stride-th): a field that stays in the cache.
  HeightField strided(map.width, map.height, map.x0, map.y0, map.dx, map.dy);
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) strided.at(i, j) = f.at(i * map.stride, j * map.stride);
  strided.outsideHeight = f.outsideHeight;
  const HeightField& field = map.stride > 1 ? strided : f;
  const double top = f.maxHeight();
  const int threads = settings.threads > 0 ? settings.threads : std::max(1, int(std::thread::hardware_concurrency()));
  std::atomic<int> next{0};
  auto work = [&] {
    for (int j = next++; j < map.height; j = next++)
      for (int i = 0; i < map.width; ++i) {
        const int si = i * map.stride, sj = j * map.stride;
        const double x = f.xAt(si), y = f.yAt(sj), h0 = f.at(si, sj);
        for (int k = 0; k < map.azimuths; ++k) {
          const double phi = 2.0 * kPi * (k + 0.5) / map.azimuths;
          map.elevation[(size_t(j) * size_t(map.width) + size_t(i)) * size_t(map.azimuths) + size_t(k)] =
              float(horizonElevation(field, R, x, y, h0, phi, settings.stepRatio, top));
        }
      }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return map;
}

}  // namespace firmament::terrain
