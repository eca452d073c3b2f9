#include "weather/weather_state.h"

#include <cstring>

namespace firmament::weather {

WeatherState::WeatherState(int nx_, int ny_, double cellSize) : nx(nx_), ny(ny_), cellSize_m(cellSize) {
  for (Field* f : {&temperature, &vapour, &cloudWater, &rain, &updraft, &cloudTop, &convectiveFraction, &cloudBase,
                   &surfaceHeatFlux, &precipitationRate, &windU, &windV, &lift})
    f->assign(cells(), 0.0f);
}

double sumField(const Field& f) {
  // Eight independent accumulators (four pairs of SSE2 lanes): the same double precision, without one
  // long dependency chain.
  using Float2 = float __attribute__((vector_size(8)));
  using Double2 = double __attribute__((vector_size(16)));
  Double2 part[4] = {};
  const float* v = f.data();
  size_t n = f.size(), i = 0;
  for (; i + 8 <= n; i += 8)
    for (size_t k = 0; k < 4; ++k) {
      Float2 x;
      std::memcpy(&x, v + i + 2 * k, sizeof x);
      part[k] += __builtin_convertvector(x, Double2);
    }
  double tail = 0.0;
  for (; i < n; ++i) tail += double(v[i]);
  const Double2 sum = (part[0] + part[1]) + (part[2] + part[3]);
  return (sum[0] + sum[1]) + tail;
}

bool anyNonZero(const Field& f) {
  // Blocks of 256 without an early exit inside (so they vectorise), then one test per block.
  const float* v = f.data();
  const size_t n = f.size();
  size_t i = 0;
  for (; i + 256 <= n; i += 256) {
    int found = 0;
    for (size_t k = 0; k < 256; ++k) found |= v[i + k] != 0.0f;
    if (found) return true;
  }
  for (; i < n; ++i)
    if (v[i] != 0.0f) return true;
  return false;
}

double WeatherState::total_kg(const Field& f) const { return sumField(f) * cellArea(); }

}  // namespace firmament::weather
