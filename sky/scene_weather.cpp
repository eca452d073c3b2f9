#include "sky/scene_weather.h"

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "astro/geodetic.h"
#include "astro/sun.h"
#include "astro/time.h"
#include "weather/weather_config.h"
#include "weather/weather_model.h"

namespace firmament {

double secondsSinceSolarMidnight(const std::string& utc, double longitude_deg) {
  const astro::UtcTime t = astro::parseUtc(utc);
  // Mean solar time = UTC + longitude / (15 deg per hour); seconds of that day, wrapped to [0, 1 d).
  const double day = 86400.0;
  const double solar = t.hour * 3600.0 + t.minute * 60.0 + t.second + longitude_deg / 15.0 * 3600.0;
  const double s = std::fmod(std::fmod(solar, day) + day, day);
  return s;
}

namespace {

using weather::WeatherModel;

// Runs `model` to model time end_s in the steps WeatherModel::advance takes from time 0
// (config.timeStep_s, the last one shortened) and returns a copy of it from before that shortened
// step (at end_s when there is none). The copy was reached by whole steps only: for any later end a
// run from time 0 takes the same whole steps up to it (end2 - t >= end1 - t >= timeStep), so running
// on from it repeats a run from midnight operation for operation.
WeatherModel runTo(WeatherModel& model, double end_s) {
  const double step = model.config().timeStep_s;
  std::optional<WeatherModel> checkpoint;
  while (model.time_s() < end_s - 1e-6) {
    const double left = end_s - model.time_s();
    if (left < step) checkpoint = model;
    model.step(std::min(step, left));
  }
  return checkpoint ? std::move(*checkpoint) : model;
}

struct WeatherCache {
  std::mutex mutex;
  std::map<std::string, CloudWeatherMap> maps;      // by weather section, location and time: a few 256^2 x 16 bytes
  std::map<std::string, WeatherModel> checkpoints;  // by weather section, location and start (midnight)
};

WeatherCache& weatherCache() {
  static WeatherCache cache;
  return cache;
}

}  // namespace

void clearSceneWeatherCache() {
  WeatherCache& cache = weatherCache();
  std::lock_guard<std::mutex> lock(cache.mutex);
  cache.maps.clear();
  cache.checkpoints.clear();
}

CloudWeatherMap cloudWeatherMapForScene(const Scene& scene, SceneWeatherInfo* info) {
  if (info) *info = {};
  if (!scene.hasSection("weather"))
    return proceduralCloudWeatherMap(uint32_t(scene.number("/clouds/seed")));

  const double latitude = scene.number("/location/latitude_deg"), longitude = scene.number("/location/longitude_deg");
  const std::string utc = scene.string("/time/utc");
  const double run_s = secondsSinceSolarMidnight(utc, longitude);
  const astro::UtcTime start = astro::addSeconds(astro::parseUtc(utc), -run_s);
  const std::string place = scene.at("/weather").dump() + "|" + std::to_string(latitude) + "|" +
                            std::to_string(longitude) + "|" + std::to_string(scene.number("/location/height_m"));
  const std::string key = place + "|" + utc;
  const std::string day = place + "|" + astro::formatUtc(start);
  WeatherCache& cache = weatherCache();
  std::optional<WeatherModel> model;
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    if (auto it = cache.maps.find(key); it != cache.maps.end()) {
      if (info) *info = {run_s, 0.0, 0.0, true, false};
      return it->second;
    }
    if (auto it = cache.checkpoints.find(day); it != cache.checkpoints.end() && it->second.time_s() <= run_s)
      model.emplace(it->second);
  }

  const auto started = std::chrono::steady_clock::now();
  const auto location = astro::GeodeticLocation::fromDegrees(latitude, longitude, scene.number("/location/height_m"));
  const bool continued = model.has_value();
  const double from_s = continued ? model->time_s() : 0.0;
  if (!continued) {
    weather::WeatherConfig config = weather::configFromJson(scene.at("/weather"));
    config.surfacePressure_Pa = weather::surfacePressureFromHeight(scene.number("/location/height_m"));
    model.emplace(config, [location, start](double t) {
      return astro::sunPosition(astro::makeAstroTime(astro::addSeconds(start, t)), location).elevation();
    });
  }
  WeatherModel checkpoint = runTo(*model, run_s);
  const weather::RegionPlacement placement{location.latitude, location.longitude, 6360000.0};
  const weather::WeatherMap w = model->map(placement);

  CloudWeatherMap m;
  m.map = w.map;
  m.width_m = w.width_m();
  m.height_m = w.height_m();
  m.skew = w.windShear_per_s * weather::WeatherMap::kSkewRiseTime_s;  // (du/dz) z 300 s: m per m
  m.source = "weather simulation";
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  if (info) *info = {run_s, run_s - from_s, ms, false, continued};
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (cache.maps.size() > 8) cache.maps.clear();
  cache.maps.emplace(key, m);
  if (cache.checkpoints.size() > 2) cache.checkpoints.clear();
  cache.checkpoints.insert_or_assign(day, std::move(checkpoint));
  return m;
}

}  // namespace firmament
