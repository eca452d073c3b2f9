#include "sky/scene_weather.h"

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

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

CloudWeatherMap cloudWeatherMapForScene(const Scene& scene, SceneWeatherInfo* info) {
  if (info) *info = {};
  if (!scene.hasSection("weather"))
    return proceduralCloudWeatherMap(uint32_t(scene.number("/clouds/seed")));

  const double latitude = scene.number("/location/latitude_deg"), longitude = scene.number("/location/longitude_deg");
  const std::string utc = scene.string("/time/utc");
  const double run_s = secondsSinceSolarMidnight(utc, longitude);
  const std::string key = scene.at("/weather").dump() + "|" + std::to_string(latitude) + "|" +
                          std::to_string(longitude) + "|" + std::to_string(scene.number("/location/height_m")) + "|" + utc;
  static std::mutex mutex;
  static std::map<std::string, CloudWeatherMap> cache;  // a few maps of 256^2 x 16 bytes
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) {
      if (info) *info = {run_s, 0.0, true};
      return it->second;
    }
  }

  const auto started = std::chrono::steady_clock::now();
  weather::WeatherConfig config = weather::configFromJson(scene.at("/weather"));
  config.surfacePressure_Pa = weather::surfacePressureFromHeight(scene.number("/location/height_m"));
  const auto location = astro::GeodeticLocation::fromDegrees(latitude, longitude, scene.number("/location/height_m"));
  const astro::UtcTime start = astro::addSeconds(astro::parseUtc(utc), -run_s);
  weather::WeatherModel model(config, [location, start](double t) {
    return astro::sunPosition(astro::makeAstroTime(astro::addSeconds(start, t)), location).elevation();
  });
  if (run_s > 0.0) model.advance(run_s);
  const weather::RegionPlacement placement{location.latitude, location.longitude, 6360000.0};
  const weather::WeatherMap w = model.map(placement);

  CloudWeatherMap m;
  m.map = w.map;
  m.width_m = w.width_m();
  m.height_m = w.height_m();
  m.skew = w.windShear_per_s * weather::WeatherMap::kSkewRiseTime_s;  // (du/dz) z 300 s: m per m
  m.source = "weather simulation";
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  if (info) *info = {run_s, ms, false};
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() > 8) cache.clear();
  cache.emplace(key, m);
  return m;
}

}  // namespace firmament
