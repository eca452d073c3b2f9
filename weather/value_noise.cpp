#include "weather/value_noise.h"

#include <algorithm>
#include <cmath>

namespace firmament::weather {

uint32_t hashCombine(uint32_t a, uint32_t b) {
  uint32_t h = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u + (a << 6) + (a >> 2));
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return h;
}

float unitFloat(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

std::vector<float> periodicNoiseField(int nx, int ny, double period_cells, int octaves, uint32_t seed) {
  std::vector<float> field(size_t(nx) * ny, 0.0f);
  double amplitude = 1.0;
  for (int o = 0; o < octaves; ++o) {
    // Lattice counts that divide the domain, so the noise is periodic.
    int gx = std::max(1, int(std::lround(nx / period_cells))), gy = std::max(1, int(std::lround(ny / period_cells)));
    uint32_t octaveSeed = hashCombine(seed, uint32_t(o) + 1u);
    auto lattice = [&](int i, int j) {
      i = ((i % gx) + gx) % gx;
      j = ((j % gy) + gy) % gy;
      return unitFloat(hashCombine(octaveSeed, uint32_t(j * gx + i))) - 0.5f;
    };
    for (int y = 0; y < ny; ++y) {
      double fy = (y + 0.5) * gy / ny;
      int j = int(std::floor(fy));
      double ty = fy - j;
      ty = ty * ty * (3.0 - 2.0 * ty);
      for (int x = 0; x < nx; ++x) {
        double fx = (x + 0.5) * gx / nx;
        int i = int(std::floor(fx));
        double tx = fx - i;
        tx = tx * tx * (3.0 - 2.0 * tx);
        double a = lattice(i, j) + tx * (lattice(i + 1, j) - lattice(i, j));
        double b = lattice(i, j + 1) + tx * (lattice(i + 1, j + 1) - lattice(i, j + 1));
        field[size_t(y) * nx + x] += float(amplitude * (a + ty * (b - a)));
      }
    }
    period_cells *= 0.5;
    amplitude *= 0.5;
  }
  double mean = 0.0, variance = 0.0;
  for (float v : field) mean += v;
  mean /= double(field.size());
  for (float v : field) variance += (v - mean) * (v - mean);
  double sd = std::sqrt(variance / double(field.size()));
  for (float& v : field) v = sd > 0.0 ? float((v - mean) / sd) : 0.0f;
  return field;
}

}  // namespace firmament::weather
