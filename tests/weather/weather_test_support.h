#pragma once
// Shared set-ups for the weather tests: a summer day at the default scene's place, small grids.
#include <numbers>

#include "astro/sun.h"
#include "weather/weather_model.h"

namespace firmament::weather::test {

inline constexpr double kLatitude = 46.55 * std::numbers::pi / 180.0;
inline constexpr double kLongitude = 7.98 * std::numbers::pi / 180.0;

// 21 June, starting 03:00 UTC (before sunrise at 46.55° N, 7.98° E): astro's sun, as the renderer's.
inline SunElevationFunction summerDay() {
  return astro::sunElevationAfter(astro::GeodeticLocation::fromDegrees(46.55, 7.98, 0.0),
                                  astro::parseUtc("2026-06-21T03:00:00Z"));
}

inline WeatherConfig smallConfig(const char* preset, int cells = 64) {
  WeatherConfig c;
  c.preset = preset;
  c.cellsX = c.cellsY = cells;
  return c;
}

// Local mean solar time (hours) of model time t for the summerDay start.
inline double localSolarHours(double t_s) { return 3.0 + t_s / 3600.0 + 7.98 / 15.0; }

}  // namespace firmament::weather::test
