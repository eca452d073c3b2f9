#pragma once
// The weather section of a scene, in SI units. configFromJson reads it from the scene's "weather" object
// (schema: core/scene_schema.json, "weather"); unknown keys, wrong types and out-of-range values are
// InputErrors that name the JSON path.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "weather/preset_schedule.h"

namespace firmament::weather {

struct WeatherConfig {
  std::string preset = "fair-weather";
  uint32_t seed = 1;
  // Prevailing wind at cloud base; shear turns into skew with height (same direction, m/s per km).
  double windSpeed_m_s = 8.0;
  double windFrom_deg = 270.0;  // meteorological: the direction it blows from, clockwise from north
  double windShear_m_s_per_km = 2.0;
  double turbulence_m_s = 1.0;  // rms of the divergence-free perturbation
  int cellsX = 256, cellsY = 256;
  double cellSize_m = 200.0;
  double timeStep_s = 60.0;
  double heatingScale = 1.0;           // multiplies the preset's absorbed solar flux
  double surfaceHeterogeneity = 0.3;   // relative standard deviation of the seeded heating map
  std::vector<PresetChange> schedule;  // preset changes after the start
  // Surface pressure, from the scene's ground height (location.height_m) by the caller.
  double surfacePressure_Pa = 101325.0;
  // Moisture exchange with the surroundings (surface evaporation, entrainment drying). Off = a closed
  // box: then vapour + cloud + rain + precipitated-out is exactly conserved (tests).
  bool exchangeWithSurroundings = true;
};

WeatherConfig configFromJson(const nlohmann::json& weatherSection);
// Surface pressure from ground height (isothermal atmosphere, scale height 8434 m).
double surfacePressureFromHeight(double height_m);

}  // namespace firmament::weather
