#include "weather/mixing.h"

#include <cmath>

namespace firmament::weather {

int Mixing::apply(Field& f, int nx, int ny, double cellSize_m, double diffusivity_m2_s, double dt_s) {
  double number = diffusivity_m2_s * dt_s / (cellSize_m * cellSize_m);
  if (number <= 0.0) return 0;
  int iterations = int(std::ceil(number / 0.2));
  const float k = float(number / iterations);
  scratch_.resize(f.size());
  for (int it = 0; it < iterations; ++it) {
    for (int j = 0; j < ny; ++j) {
      const float* row = &f[size_t(j) * nx];
      const float* north = &f[size_t(j + 1 == ny ? 0 : j + 1) * nx];
      const float* south = &f[size_t(j == 0 ? ny - 1 : j - 1) * nx];
      float* out = &scratch_[size_t(j) * nx];
      // Edges wrap; the interior loop is branch-free so it vectorises.
      out[0] = row[0] + k * (row[1] + row[nx - 1] + north[0] + south[0] - 4.0f * row[0]);
      for (int i = 1; i < nx - 1; ++i)
        out[i] = row[i] + k * (row[i + 1] + row[i - 1] + north[i] + south[i] - 4.0f * row[i]);
      out[nx - 1] = row[nx - 1] + k * (row[0] + row[nx - 2] + north[nx - 1] + south[nx - 1] - 4.0f * row[nx - 1]);
    }
    f.swap(scratch_);
  }
  return iterations;
}

}  // namespace firmament::weather
