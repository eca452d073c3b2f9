#include "clouds/blue_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atmosphere/reference_random.h"

namespace firmament {

std::vector<float> blueNoiseMask(int size, uint32_t seed) {
  const int n = size * size;
  // Kernel exp(-d^2 / (2 sigma^2)) for every toroidal offset (dx, dy).
  const double sigma = 1.5;
  std::vector<double> kernel(static_cast<size_t>(n));
  for (int dy = 0; dy < size; ++dy)
    for (int dx = 0; dx < size; ++dx) {
      const int ex = std::min(dx, size - dx), ey = std::min(dy, size - dy);
      kernel[size_t(dy * size + dx)] = std::exp(-double(ex * ex + ey * ey) / (2.0 * sigma * sigma));
    }
  std::vector<double> energy(size_t(n), 0.0);
  std::vector<int> rank(size_t(n), -1);
  reference::Random random(seed, 0x626c7565ull);  // "blue"
  // A tiny seeded perturbation breaks ties between equal voids so the seed shapes the whole mask.
  std::vector<double> tieBreak(static_cast<size_t>(n));
  for (double& t : tieBreak) t = 1e-9 * random.uniform();
  int next = int(random.uniform() * n) % n;
  for (int r = 0; r < n; ++r) {
    rank[size_t(next)] = r;
    const int px = next % size, py = next / size;
    double best = std::numeric_limits<double>::infinity();
    int bestIndex = -1;
    for (int y = 0; y < size; ++y) {
      const int dy = (y - py + size) % size;
      for (int x = 0; x < size; ++x) {
        const size_t i = size_t(y * size + x);
        energy[i] += kernel[size_t(dy * size + (x - px + size) % size)];
        if (rank[i] < 0 && energy[i] + tieBreak[i] < best) {
          best = energy[i] + tieBreak[i];
          bestIndex = int(i);
        }
      }
    }
    if (bestIndex < 0) break;
    next = bestIndex;
  }
  std::vector<float> mask(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) mask[size_t(i)] = float((double(rank[size_t(i)]) + 0.5) / double(n));
  return mask;
}

}  // namespace firmament
