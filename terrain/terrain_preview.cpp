#include "terrain/terrain_preview.h"

#include <algorithm>
#include <cmath>

namespace firmament::terrain {

std::vector<uint8_t> hillshadeRgb(const HeightField& f) {
  std::vector<uint8_t> rgb(size_t(f.nx) * size_t(f.ny) * 3);
  const double lo = f.minHeight(), hi = f.maxHeight(), range = std::max(hi - lo, 1e-6);
  // Light from azimuth 315° (north-west), 45° up: (east, north, up).
  const double s = std::sqrt(0.5);
  const glm::dvec3 light(-s * s, s * s, s);
  static const double kTint[4][3] = {{0.35, 0.55, 0.30}, {0.75, 0.70, 0.45}, {0.55, 0.45, 0.40}, {0.97, 0.97, 0.97}};
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, f.nx - 1);
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, f.ny - 1);
      const double gx = (f.at(i1, j) - f.at(i0, j)) / ((i1 - i0) * f.dx);
      const double gy = (f.at(i, j1) - f.at(i, j0)) / ((j1 - j0) * f.dy);
      const glm::dvec3 n = glm::normalize(glm::dvec3(-gx, -gy, 1.0));
      const double shade = 0.2 + 0.8 * std::max(0.0, glm::dot(n, light));
      const double e = std::clamp((f.at(i, j) - lo) / range, 0.0, 1.0) * 3.0;
      const int k = std::min(int(e), 2);
      const double w = e - k;
      uint8_t* p = rgb.data() + (size_t(f.ny - 1 - j) * size_t(f.nx) + size_t(i)) * 3;
      for (int c = 0; c < 3; ++c) {
        const double tint = kTint[k][c] + (kTint[k + 1][c] - kTint[k][c]) * w;
        p[c] = uint8_t(std::lround(255.0 * std::clamp(tint * shade, 0.0, 1.0)));
      }
    }
  return rgb;
}

}  // namespace firmament::terrain
