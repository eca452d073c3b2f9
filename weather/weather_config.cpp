#include "weather/weather_config.h"

#include <cmath>
#include <set>

#include "core/error.h"
#include "weather/physical_constants.h"

namespace firmament::weather {
namespace {

using nlohmann::json;

void rejectUnknownKeys(const json& object, const std::string& path, const std::set<std::string>& allowed) {
  if (!object.is_object()) throw InputError(path + ": expected an object");
  for (auto it = object.begin(); it != object.end(); ++it)
    if (!allowed.count(it.key())) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(path + "/" + it.key() + ": unknown key (allowed: " + list + ")");
    }
}

double number(const json& object, const std::string& key, const std::string& path, double fallback, double lo,
              double hi) {
  if (!object.contains(key)) return fallback;
  const json& v = object.at(key);
  if (!v.is_number()) throw InputError(path + "/" + key + ": expected a number");
  double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi)
    throw InputError(path + "/" + key + ": " + v.dump() + " is outside [" + json(lo).dump() + ", " + json(hi).dump() +
                     "]");
  return d;
}

long long integer(const json& object, const std::string& key, const std::string& path, long long fallback, long long lo,
                  long long hi) {
  if (!object.contains(key)) return fallback;
  const json& v = object.at(key);
  if (!v.is_number_integer() && !v.is_number_unsigned()) throw InputError(path + "/" + key + ": expected an integer");
  long long d = v.get<long long>();
  if (d < lo || d > hi)
    throw InputError(path + "/" + key + ": " + v.dump() + " is outside [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  return d;
}

std::string presetName(const json& object, const std::string& key, const std::string& path,
                       const std::string& fallback) {
  if (!object.contains(key)) return fallback;
  const json& v = object.at(key);
  if (!v.is_string()) throw InputError(path + "/" + key + ": expected a string");
  std::string s = v.get<std::string>();
  if (!isPresetName(s)) {
    std::string list;
    for (const auto& n : presetNames()) list += (list.empty() ? "" : ", ") + n;
    throw InputError(path + "/" + key + ": '" + s + "' is not a preset (allowed: " + list + ")");
  }
  return s;
}

}  // namespace

double surfacePressureFromHeight(double height_m) {
  return kSeaLevelPressure * std::exp(-height_m / kPressureScaleHeight);
}

WeatherConfig configFromJson(const json& w) {
  const std::string path = "/weather";
  WeatherConfig c;
  if (w.is_null()) return c;
  // start_utc (when the run starts) belongs to the caller that places the run in time (sky/scene_weather.h).
  rejectUnknownKeys(w, path,
                    {"preset", "seed", "wind", "grid", "time_step_s", "heating_scale", "surface_heterogeneity",
                     "schedule", "start_utc"});
  c.preset = presetName(w, "preset", path, c.preset);
  c.seed = uint32_t(integer(w, "seed", path, c.seed, 0, 4294967295LL));
  if (w.contains("wind")) {
    const json& wind = w.at("wind");
    rejectUnknownKeys(wind, path + "/wind", {"speed_m_s", "from_deg", "shear_m_s_per_km", "turbulence_m_s"});
    c.windSpeed_m_s = number(wind, "speed_m_s", path + "/wind", c.windSpeed_m_s, 0, 100);
    c.windFrom_deg = number(wind, "from_deg", path + "/wind", c.windFrom_deg, -360, 360);
    c.windShear_m_s_per_km = number(wind, "shear_m_s_per_km", path + "/wind", c.windShear_m_s_per_km, -20, 20);
    c.turbulence_m_s = number(wind, "turbulence_m_s", path + "/wind", c.turbulence_m_s, 0, 10);
  }
  if (w.contains("grid")) {
    const json& g = w.at("grid");
    rejectUnknownKeys(g, path + "/grid", {"cells_x", "cells_y", "cell_size_m"});
    c.cellsX = int(integer(g, "cells_x", path + "/grid", c.cellsX, 8, 4096));
    c.cellsY = int(integer(g, "cells_y", path + "/grid", c.cellsY, 8, 4096));
    c.cellSize_m = number(g, "cell_size_m", path + "/grid", c.cellSize_m, 10, 10000);
  }
  c.timeStep_s = number(w, "time_step_s", path, c.timeStep_s, 1, 86400);
  c.heatingScale = number(w, "heating_scale", path, c.heatingScale, 0, 5);
  c.surfaceHeterogeneity = number(w, "surface_heterogeneity", path, c.surfaceHeterogeneity, 0, 1);
  if (w.contains("schedule")) {
    const json& s = w.at("schedule");
    if (!s.is_array()) throw InputError(path + "/schedule: expected an array");
    if (s.size() > 64) throw InputError(path + "/schedule: at most 64 changes");
    for (size_t i = 0; i < s.size(); ++i) {
      std::string p = path + "/schedule/" + std::to_string(i);
      rejectUnknownKeys(s[i], p, {"at_h", "preset", "transition_h"});
      if (!s[i].contains("preset")) throw InputError(p + ": 'preset' is required");
      if (!s[i].contains("at_h")) throw InputError(p + ": 'at_h' is required");
      PresetChange change;
      change.at_s = number(s[i], "at_h", p, 0, 0, 8760) * 3600.0;
      change.preset = presetName(s[i], "preset", p, "");
      change.transition_s = number(s[i], "transition_h", p, 1.0, 0, 48) * 3600.0;
      c.schedule.push_back(change);
    }
  }
  return c;
}

}  // namespace firmament::weather
