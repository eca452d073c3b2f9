#include "sky/scene_weather.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "astro/geodetic.h"
#include "astro/sun.h"
#include "astro/time.h"
#include "core/error.h"
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

double secondsBetween(const astro::UtcTime& from, const astro::UtcTime& to) {
  const astro::JulianDate a = astro::makeAstroTime(from).utcJulian, b = astro::makeAstroTime(to).utcJulian;
  return ((b.dayStart - a.dayStart) + (b.dayFraction - a.dayFraction)) * 86400.0;
}

}  // namespace

astro::UtcTime sceneWeatherStart(const Scene& scene) {
  const std::string utc = scene.string("/time/utc");
  const astro::UtcTime time = astro::parseUtc(utc);
  if (!scene.root().contains("weather") || !scene.at("/weather").value("start_utc", nlohmann::json()).is_string())
    return astro::addSeconds(time, -secondsSinceSolarMidnight(utc, scene.number("/location/longitude_deg")));
  const std::string text = scene.string("/weather/start_utc");
  astro::UtcTime start;
  try {
    start = astro::parseUtc(text);
  } catch (const InputError& e) {
    throw InputError(scene.source() + ": /weather/start_utc: " + e.what());
  }
  const double run = secondsBetween(start, time);
  if (run < 0.0)
    throw InputError(scene.source() + ": /weather/start_utc " + text + " is after /time/utc " + utc +
                     "; allowed: a start at or before the scene's time, at most 7 days before it");
  if (run > kSceneWeatherMaxRun_s)
    throw InputError(scene.source() + ": /weather/start_utc " + text + " is " + std::to_string(run / 86400.0) +
                     " days before /time/utc " + utc + "; allowed: at most 7 days before it");
  return start;
}

double sceneWeatherRunSeconds(const Scene& scene) {
  if (!scene.root().contains("weather") || !scene.at("/weather").value("start_utc", nlohmann::json()).is_string())
    return secondsSinceSolarMidnight(scene.string("/time/utc"), scene.number("/location/longitude_deg"));
  return std::clamp(secondsBetween(sceneWeatherStart(scene), astro::parseUtc(scene.string("/time/utc"))), 0.0,
                    kSceneWeatherMaxRun_s);
}

namespace {

using weather::WeatherModel;

// Runs `model` by whole steps of config.timeStep_s while one more fits before end_s: the steps a run
// from midnight to any later time takes too, so running on from the result repeats such a run
// operation for operation.
void runWholeSteps(WeatherModel& model, double end_s) {
  const double step = model.config().timeStep_s;
  while (model.time_s() + step <= end_s + 1e-6) model.step(step);
}

CloudWeatherMap cloudMapOf(const WeatherModel& model, const weather::RegionPlacement& placement) {
  const weather::WeatherMap w = model.map(placement);
  CloudWeatherMap m;
  m.map = w.map;
  m.width_m = w.width_m();
  m.height_m = w.height_m();
  m.skew = w.windShear_per_s * weather::WeatherMap::kSkewRiseTime_s;  // (du/dz) z 300 s: m per m
  m.source = "weather simulation";
  m.sharpCoverage = true;  // 200 m cells: coverage jumps within one or two
  return m;
}

// (1 - w) a + w b, texel by texel (maps of one model: same size and region).
CloudWeatherMap interpolate(const CloudWeatherMap& a, const CloudWeatherMap& b, double w) {
  CloudWeatherMap m = a;
  const float wf = float(w);
  for (size_t i = 0; i < m.map.pixels.size(); ++i)
    m.map.pixels[i] = (1.0f - wf) * a.map.pixels[i] + wf * b.map.pixels[i];
  if (a.skew != b.skew) m.skew = (1.0 - w) * a.skew + w * b.skew;
  return m;
}

// The model at a whole step and its maps there and one step later.
struct Checkpoint {
  WeatherModel model;
  CloudWeatherMap now, next;
};

struct WeatherCache {
  std::mutex mutex;
  std::map<std::string, CloudWeatherMap> maps;    // by weather section, location and time: a few 256^2 x 16 bytes
  std::map<std::string, Checkpoint> checkpoints;  // by weather section, location and start (midnight)
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
  if (!scene.hasSection("weather")) return proceduralCloudWeatherMap(uint32_t(scene.number("/clouds/seed")));

  const double latitude = scene.number("/location/latitude_deg"), longitude = scene.number("/location/longitude_deg");
  const std::string utc = scene.string("/time/utc");
  const astro::UtcTime start = sceneWeatherStart(scene);
  const double run_s = sceneWeatherRunSeconds(scene);
  const std::string place = scene.at("/weather").dump() + "|" + std::to_string(latitude) + "|" +
                            std::to_string(longitude) + "|" + std::to_string(scene.number("/location/height_m"));
  const std::string key = place + "|" + utc;
  const std::string day = place + "|" + astro::formatUtc(start);
  WeatherCache& cache = weatherCache();
  std::optional<Checkpoint> from;
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    if (auto it = cache.maps.find(key); it != cache.maps.end()) {
      if (info) *info = {run_s, 0.0, 0.0, true, false};
      return it->second;
    }
    if (auto it = cache.checkpoints.find(day);
        it != cache.checkpoints.end() && it->second.model.time_s() <= run_s + 1e-6)
      from.emplace(it->second);
  }

  const auto started = std::chrono::steady_clock::now();
  const auto location = astro::GeodeticLocation::fromDegrees(latitude, longitude, scene.number("/location/height_m"));
  const weather::RegionPlacement placement{location.latitude, location.longitude, 6360000.0};
  const bool continued = from.has_value();
  const double from_s = continued ? from->model.time_s() : 0.0;
  if (!continued) {
    weather::WeatherConfig config = weather::configFromJson(scene.at("/weather"));
    config.surfacePressure_Pa = weather::surfacePressureFromHeight(scene.number("/location/height_m"));
    WeatherModel model(config, astro::sunElevationAfter(location, start));
    from.emplace(Checkpoint{std::move(model), {}, {}});
  }
  // The map between two whole steps is the linear interpolation of theirs: the model's operators act
  // per step, so a shortened last step would not be continuous in time (a 30 fps sequence's maps
  // would jump by up to 0.035 in coverage from frame to frame).
  Checkpoint& c = *from;
  const double step = c.model.config().timeStep_s;
  const double before = c.model.time_s();
  runWholeSteps(c.model, run_s);
  if (!continued || c.model.time_s() != before) {
    c.now = cloudMapOf(c.model, placement);
    WeatherModel next = c.model;
    next.step(step);
    c.next = cloudMapOf(next, placement);
  }
  const double w = std::clamp((run_s - c.model.time_s()) / step, 0.0, 1.0);
  const CloudWeatherMap m = w <= 1e-9 ? c.now : interpolate(c.now, c.next, w);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  if (info) *info = {run_s, c.model.time_s() - from_s, ms, false, continued};
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (cache.maps.size() > 8) cache.maps.clear();
  cache.maps.emplace(key, m);
  if (cache.checkpoints.size() > 2) cache.checkpoints.clear();
  cache.checkpoints.insert_or_assign(day, std::move(c));
  return m;
}

}  // namespace firmament
