#pragma once
// The weather map a scene's clouds read (docs/clouds/weather-map.md): composition of weather/ (the
// CPU simulation) and clouds/ (which knows only CloudWeatherMap).
//
// - A `weather` section: the simulation runs from its start (sceneWeatherStart: weather.start_utc, or
//   the local mean solar midnight before the scene's time, solar time = UTC + longitude / 15 degrees
//   per hour) up to the scene's time (time.utc), so the map holds the day's convection so far; the
//   `weather` command runs the same simulation from the same start, so both show one timeline. Its map (coverage, type,
//   precipitation, top) is placed on the region centred on the scene's location, with the shear skew.
//   The model runs whole steps (time_step_s); a time between two steps gets the linear interpolation
//   of their maps, so the map is continuous in time (a sequence's frames change it a little each).
//   Cached in memory by the weather section's hash, the location and the time. A later time of the
//   same day (a sequence's or time-lapse's next frame) continues from the last run's checkpoint, the
//   model at its last whole step, instead of running from midnight again: a run from midnight takes
//   the same whole steps, so the continued map is bit for bit the one a run from midnight gives.
// - Otherwise: the procedural map of the cloud seed (clouds/cloud_weather_map.h).
#include "astro/time.h"
#include "clouds/cloud_weather_map.h"
#include "core/scene.h"

namespace firmament {

struct SceneWeatherInfo {
  double simulated_s = 0.0;   // model time of the map since the simulation's start (0 for the procedural map)
  double stepped_s = 0.0;     // model time this call ran in whole steps (from 0 or a checkpoint; 0 when cached)
  double milliseconds = 0.0;  // wall clock of the simulation (0 when cached or procedural)
  bool cached = false;
  bool continued = false;  // run on from an earlier time's checkpoint
};

// Forgets the maps and checkpoints held in memory (tests: a run from midnight after a continued one).
void clearSceneWeatherCache();

// The map for `scene` (which must have a clouds section; the seed comes from it).
CloudWeatherMap cloudWeatherMapForScene(const Scene& scene, SceneWeatherInfo* info = nullptr);

// The most model time a scene's simulation may run before the scene's time (a week: ~14 s of weather).
inline constexpr double kSceneWeatherMaxRun_s = 7.0 * 86400.0;

// When the scene's weather simulation starts: /weather/start_utc when the scene sets it, else the local
// mean solar midnight before /time/utc. InputError (exit 2) for a start after the scene's time or more
// than kSceneWeatherMaxRun_s before it.
astro::UtcTime sceneWeatherStart(const Scene& scene);

// Model seconds from sceneWeatherStart(scene) to the scene's time, in [0, kSceneWeatherMaxRun_s].
double sceneWeatherRunSeconds(const Scene& scene);

// Seconds from the local mean solar midnight before `utc` at longitude `longitude_deg` up to `utc`,
// in [0, 86400).
double secondsSinceSolarMidnight(const std::string& utc, double longitude_deg);

}  // namespace firmament
