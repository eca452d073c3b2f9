#include "weather/weather_state.h"

namespace firmament::weather {

WeatherState::WeatherState(int nx_, int ny_, double cellSize) : nx(nx_), ny(ny_), cellSize_m(cellSize) {
  for (Field* f : {&temperature, &vapour, &cloudWater, &rain, &updraft, &cloudTop, &convectiveFraction,
                   &cloudBase, &surfaceHeatFlux, &precipitationRate, &windU, &windV, &lift})
    f->assign(cells(), 0.0f);
}

double sumField(const Field& f) {
  // Four independent accumulators: the same double precision, without one long dependency chain.
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
  size_t n = f.size(), i = 0;
  for (; i + 4 <= n; i += 4) {
    a += f[i];
    b += f[i + 1];
    c += f[i + 2];
    d += f[i + 3];
  }
  for (; i < n; ++i) a += f[i];
  return (a + b) + (c + d);
}

double WeatherState::total_kg(const Field& f) const { return sumField(f) * cellArea(); }

}  // namespace firmament::weather
