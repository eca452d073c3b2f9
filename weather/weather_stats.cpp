#include "weather/weather_stats.h"

#include <algorithm>
#include <cstdio>

#include "weather/surface_heating.h"

namespace firmament::weather {

WeatherStats computeStats(const WeatherState& s) {
  WeatherStats out;
  out.time_h = s.time_s / 3600.0;
  double coverSum = 0.0, topWeighted = 0.0, topWeight = 0.0;
  size_t raining = 0, cb = 0;
  for (size_t c = 0; c < s.cells(); ++c) {
    double cover = cloudCover(s.cloudWater[c]);
    coverSum += cover;
    if (cover > 0.1) {
      topWeighted += cover * s.cloudTop[c];
      topWeight += cover;
      out.maxTop_m = std::max(out.maxTop_m, double(s.cloudTop[c]));
      if (s.cloudTop[c] >= 7000.0f && s.convectiveFraction[c] > 0.5f) ++cb;
    }
    if (s.precipitationRate[c] * 3600.0f > 0.1f) ++raining;
  }
  double n = double(s.cells());
  out.cloudFraction = coverSum / n;
  out.meanTop_m = topWeight > 0.0 ? topWeighted / topWeight : 0.0;
  out.precipAreaFraction = double(raining) / n;
  out.cumulonimbusFraction = double(cb) / n;
  out.waterTotal_kg = s.waterTotal_kg();
  out.precipOut_kg = s.precipitatedOut_kg;
  return out;
}

std::string statsCsvRow(const WeatherStats& s) {
  char line[256];
  std::snprintf(line, sizeof line, "%.4f,%.6f,%.1f,%.1f,%.6f,%.6e,%.6e", s.time_h, s.cloudFraction, s.meanTop_m,
                s.maxTop_m, s.precipAreaFraction, s.waterTotal_kg, s.precipOut_kg);
  return line;
}

}  // namespace firmament::weather
