#pragma once
// Domain statistics of a state, as written to stats.csv.
#include <string>

#include "weather/weather_state.h"

namespace firmament::weather {

struct WeatherStats {
  double time_h = 0.0;
  double cloudFraction = 0.0;         // mean cloud cover (cover = 1 − exp(−LWP/0.05 kg m⁻²))
  double meanTop_m = 0.0;             // cover-weighted mean cloud top over cells with cover > 0.1 (0 if none)
  double maxTop_m = 0.0;              // over cells with cover > 0.1
  double precipAreaFraction = 0.0;    // share of cells with rain at the ground > 0.1 mm/h
  double waterTotal_kg = 0.0;         // vapour + cloud + rain
  double precipOut_kg = 0.0;          // rain that reached the ground since the start
  double cumulonimbusFraction = 0.0;  // share of cells with cover > 0.1 and top ≥ 7 km and convective
};

WeatherStats computeStats(const WeatherState& state);

inline const char* statsCsvHeader() {
  return "time_h,cloud_fraction,mean_top_m,max_top_m,precip_area_fraction,water_total_kg,precip_out_kg";
}
std::string statsCsvRow(const WeatherStats& s);

}  // namespace firmament::weather
