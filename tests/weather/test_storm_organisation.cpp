// Storm organisation on a thunderstorm afternoon: cumulonimbus in separate cells and lines, not over the
// whole domain; no new cells under the cold pools of earlier storms; new cells preferentially near
// their edges, where the outflow's convergence lifts the air (convection.h, wind_field.h).
//
// Measured every 10 min from 10:00 to 17:30 local solar time on 96² cells (19.2 km), two seeds pooled:
//   - Cb: cells with cover > 0.1, top ≥ 7 km, convective (as in WeatherStats);
//   - cold pool: T′ at least 0.5 K below the domain mean;
//   - new trigger: a cell with an updraft > 1 m/s that had none 10 min before;
//   - trigger density in a distance class: new triggers / cell-samples in that class, the distance being
//     to the nearest cold-pool cell 10 min before (periodic, chamfer metric).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <vector>

#include "tests/weather/weather_test_support.h"
#include "weather/surface_heating.h"

using namespace firmament::weather;

namespace {

// Distance (cells) from every cell to the nearest marked one, periodic; two chamfer sweeps (3-4 metric
// scaled to 1 and √2; within 8 % of Euclidean).
std::vector<float> distanceTo(const std::vector<char>& mask, int nx, int ny) {
  std::vector<float> d(mask.size(), 1e9f);
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) d[i] = 0.0f;
  auto relax = [&](int i, int j, int di, int dj) {
    float& v = d[size_t(j) * nx + i];
    int a = (i + di + nx) % nx, b = (j + dj + ny) % ny;
    v = std::min(v, d[size_t(b) * nx + a] + (di != 0 && dj != 0 ? 1.4142f : 1.0f));
  };
  for (int sweep = 0; sweep < 2; ++sweep) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        relax(i, j, -1, -1), relax(i, j, 0, -1), relax(i, j, 1, -1), relax(i, j, -1, 0);
      }
    for (int j = ny - 1; j >= 0; --j)
      for (int i = nx - 1; i >= 0; --i) {
        relax(i, j, 1, 1), relax(i, j, 0, 1), relax(i, j, -1, 1), relax(i, j, 1, 0);
      }
  }
  return d;
}

// Separate 4-connected regions of at least `minCells` cells, periodic.
int regions(const std::vector<char>& mask, int nx, int ny, int minCells) {
  std::vector<char> seen(mask.size(), 0);
  int count = 0;
  for (size_t start = 0; start < mask.size(); ++start) {
    if (!mask[start] || seen[start]) continue;
    int size = 0;
    std::deque<size_t> queue{start};
    seen[start] = 1;
    while (!queue.empty()) {
      size_t c = queue.front();
      queue.pop_front();
      ++size;
      int i = int(c % nx), j = int(c / nx);
      const int offsets[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (auto& o : offsets) {
        size_t k = size_t((j + o[1] + ny) % ny) * nx + size_t((i + o[0] + nx) % nx);
        if (mask[k] && !seen[k]) seen[k] = 1, queue.push_back(k);
      }
    }
    if (size >= minCells) ++count;
  }
  return count;
}

struct Organisation {
  double peakCb = 0.0;
  int mostRegions = 0;
  // Distance classes: inside a pool, (0, 1] km, (1, 4] km, beyond 4 km.
  double triggers[4] = {}, samples[4] = {};
};

void observe(uint32_t seed, Organisation& o) {
  WeatherConfig c = test::smallConfig("thunderstorm", 96);
  c.seed = seed;
  WeatherModel model(c, test::summerDay());
  model.advance(6.5 * 3600.0);  // 10:02 local solar time
  const WeatherState& s = model.state();
  const size_t n = s.cells();
  auto poolMask = [&] {
    double mean = 0.0;
    for (float t : s.temperature) mean += t;
    mean /= double(n);
    std::vector<char> pool(n);
    for (size_t i = 0; i < n; ++i) pool[i] = s.temperature[i] < float(mean) - 0.5f;
    return pool;
  };
  std::vector<float> previousUpdraft = s.updraft;
  std::vector<char> previousPool = poolMask();
  for (int k = 0; k < 45; ++k) {
    model.advance(600.0);
    std::vector<char> cb(n);
    size_t cbCells = 0;
    for (size_t i = 0; i < n; ++i) {
      cb[i] = s.cloudTop[i] >= 7000.0f && cloudCover(s.cloudWater[i]) > 0.1f && s.convectiveFraction[i] > 0.5f;
      cbCells += size_t(cb[i]);
    }
    o.peakCb = std::max(o.peakCb, double(cbCells) / double(n));
    o.mostRegions = std::max(o.mostRegions, regions(cb, s.nx, s.ny, 4));
    if (std::find(previousPool.begin(), previousPool.end(), 1) != previousPool.end()) {
      std::vector<float> d = distanceTo(previousPool, s.nx, s.ny);
      for (size_t i = 0; i < n; ++i) {
        double km = d[i] * c.cellSize_m / 1000.0;
        int klass = km == 0.0 ? 0 : km <= 1.0 ? 1 : km <= 4.0 ? 2 : 3;
        o.samples[klass] += 1.0;
        if (s.updraft[i] > 1.0f && previousUpdraft[i] == 0.0f) o.triggers[klass] += 1.0;
      }
    }
    previousUpdraft = s.updraft;
    previousPool = poolMask();
  }
}

}  // namespace

TEST(StormOrganisation, IsolatedCellsSuppressedUnderPoolsTriggeredAtTheirEdges) {
  Organisation o;
  for (uint32_t seed : {1u, 2u}) observe(seed, o);
  double density[4];
  const char* names[4] = {"inside cold pools", "0-1 km outside", "1-4 km outside", "beyond 4 km"};
  for (int k = 0; k < 4; ++k) {
    density[k] = o.samples[k] > 0 ? o.triggers[k] / o.samples[k] : 0.0;
    std::printf("  new cells %-18s: %6.0f of %8.0f cell-samples, density %.4f\n", names[k], o.triggers[k], o.samples[k],
                density[k]);
  }
  std::printf("  peak Cb area fraction %.3f; most separate Cb regions at once %d\n", o.peakCb, o.mostRegions);
  // Not domain-wide: at most half the domain is Cb at any time, in more than one region.
  EXPECT_GT(o.peakCb, 0.01);
  EXPECT_LT(o.peakCb, 0.5);
  EXPECT_GE(o.mostRegions, 2);
  // Enough new cells to measure, and enough cold pool to measure around.
  ASSERT_GT(o.triggers[1] + o.triggers[2] + o.triggers[3], 200.0);
  ASSERT_GT(o.samples[0], 1000.0);
  // Suppression: new cells under a cold pool are at most a fifth as frequent as near its edge.
  EXPECT_LT(density[0], 0.2 * density[2]);
  // Triggering at the edges: new cells are more frequent 1–4 km outside the pools than far from them.
  EXPECT_GT(density[2], 1.2 * density[3]);
}
