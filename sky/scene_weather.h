#pragma once
// The weather map a scene's clouds read (docs/clouds/weather-map.md): composition of weather/ (the
// CPU simulation) and clouds/ (which knows only CloudWeatherMap).
//
// - A `weather` section: the simulation runs from the local mean solar midnight before the scene's
//   time (time.utc; solar time = UTC + longitude / 15 degrees per hour) up to that time, so the map
//   holds the day's convection so far (0 to 24 h of model time); its map (coverage, type,
//   precipitation, top) is placed on the region centred on the scene's location, with the shear skew.
//   The model runs whole steps (time_step_s); a time between two steps gets the linear interpolation
//   of their maps, so the map is continuous in time (a sequence's frames change it a little each).
//   Cached in memory by the weather section's hash, the location and the time. A later time of the
//   same day (a sequence's or time-lapse's next frame) continues from the last run's checkpoint, the
//   model at its last whole step, instead of running from midnight again: a run from midnight takes
//   the same whole steps, so the continued map is bit for bit the one a run from midnight gives.
// - Otherwise: the procedural map of the cloud seed (clouds/cloud_weather_map.h).
#include "clouds/cloud_weather_map.h"
#include "core/scene.h"

namespace firmament {

struct SceneWeatherInfo {
  double simulated_s = 0.0;   // model time of the map since the solar midnight (0 for the procedural map)
  double stepped_s = 0.0;     // model time this call ran in whole steps (from 0 or a checkpoint; 0 when cached)
  double milliseconds = 0.0;  // wall clock of the simulation (0 when cached or procedural)
  bool cached = false;
  bool continued = false;  // run on from an earlier time's checkpoint
};

// Forgets the maps and checkpoints held in memory (tests: a run from midnight after a continued one).
void clearSceneWeatherCache();

// The map for `scene` (which must have a clouds section; the seed comes from it).
CloudWeatherMap cloudWeatherMapForScene(const Scene& scene, SceneWeatherInfo* info = nullptr);

// Seconds from the local mean solar midnight before `utc` at longitude `longitude_deg` up to `utc`,
// in [0, 86400).
double secondsSinceSolarMidnight(const std::string& utc, double longitude_deg);

}  // namespace firmament
