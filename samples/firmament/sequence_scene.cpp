#include "samples/firmament/sequence_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "astro/time.h"
#include "core/error.h"
#include "core/hash.h"
#include "sky/scene_weather.h"

namespace firmament::cli {

Scene SequenceSceneSource::load(const std::vector<std::string>& extra) const {
  std::vector<std::string> o = overrides;
  o.insert(o.end(), extra.begin(), extra.end());
  return path.empty() ? Scene::parse(defaultSceneText(), kDefaultSceneName, o) : Scene::load(path, o);
}

CameraPose cameraPoseOf(const Scene& scene) {
  return {scene.number("/camera/yaw_deg"), scene.number("/camera/pitch_deg"),
          scene.number("/camera/height_above_ground_m"), scene.number("/camera/fov_deg")};
}

Scene sequenceFrameScene(const SequenceSceneSource& source, const Scene& base, double elapsed_s,
                         const std::optional<CameraPose>& pose) {
  std::vector<std::string> o;
  if (pose) {
    o.push_back("/camera/yaw_deg=" + roundTripDecimal(pose->yaw_deg));
    o.push_back("/camera/pitch_deg=" + roundTripDecimal(pose->pitch_deg));
    o.push_back("/camera/height_above_ground_m=" + roundTripDecimal(pose->height_above_ground_m));
    o.push_back("/camera/fov_deg=" + roundTripDecimal(pose->fov_deg));
  }
  if (base.hasSection("clouds"))
    o.push_back("/clouds/time_s=" + roundTripDecimal(base.number("/clouds/time_s") + elapsed_s));
  // The sun follows the clock when the scene takes it from time and location.
  if (!base.hasSection("sun"))
    o.push_back("/time/utc=" +
                astro::formatUtc(astro::addSeconds(astro::parseUtc(base.string("/time/utc")), elapsed_s)));
  // One weather simulation for the whole sequence: it runs from the solar midnight before the first
  // frame (or the scene's own /weather/start_utc) to every frame, so a sequence that crosses a solar
  // midnight runs on through the night instead of starting the day again.
  if (base.hasSection("weather") && !base.at("/weather").contains("start_utc")) {
    const double run_s = sceneWeatherRunSeconds(base) + elapsed_s;
    if (run_s > kSceneWeatherMaxRun_s)
      throw InputError(base.source() + ": a frame " + roundTripDecimal(elapsed_s / 3600.0) + " h after the first is " +
                       roundTripDecimal(run_s / 86400.0) +
                       " days of weather after the solar midnight before the first frame; allowed: at most 7 days");
    o.push_back("/weather/start_utc=" + astro::formatUtc(sceneWeatherStart(base)));
  }
  return source.load(o);
}

CameraPath CameraPath::load(const std::string& file, const CameraPose& sceneCamera) {
  std::ifstream in(file);
  if (!in) throw InputError("--camera-path " + file + ": cannot read the file");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const std::exception& e) {
    throw InputError("--camera-path " + file + ": not JSON: " + e.what());
  }
  const std::string form =
      "; allowed: {\"keys\": [{\"time_s\": S, \"yaw_deg\": Y, \"pitch_deg\": P[, \"height_above_ground_m\": H]"
      "[, \"fov_deg\": F]}, ...]}";
  if (!j.is_object() || !j.contains("keys") || !j["keys"].is_array() || j["keys"].empty() || j.size() != 1)
    throw InputError("--camera-path " + file + ": needs one field, a non-empty array \"keys\"" + form);
  CameraPath path;
  for (size_t i = 0; i < j["keys"].size(); ++i) {
    const nlohmann::json& k = j["keys"][i];
    const std::string where = "--camera-path " + file + ": /keys/" + std::to_string(i);
    if (!k.is_object()) throw InputError(where + ": not an object" + form);
    for (const auto& [name, value] : k.items()) {
      if (name != "time_s" && name != "yaw_deg" && name != "pitch_deg" && name != "height_above_ground_m" &&
          name != "fov_deg")
        throw InputError(where + ": unknown field \"" + name + "\"" + form);
      if (!value.is_number()) throw InputError(where + "/" + name + ": not a number");
    }
    for (const char* required : {"time_s", "yaw_deg", "pitch_deg"})
      if (!k.contains(required)) throw InputError(where + ": missing \"" + required + "\"" + form);
    Key key{
        k["time_s"].get<double>(),
        {k["yaw_deg"].get<double>(), k["pitch_deg"].get<double>(),
         k.value("height_above_ground_m", sceneCamera.height_above_ground_m), k.value("fov_deg", sceneCamera.fov_deg)}};
    if (!(key.time_s >= 0.0) || key.time_s > 1e7) throw InputError(where + "/time_s: allowed: 0 to 1e7 s");
    if (!path.keys_.empty() && !(key.time_s > path.keys_.back().time_s))
      throw InputError(where + "/time_s: the keys' times must increase strictly");
    if (!(std::abs(key.pose.yaw_deg) <= 3600.0)) throw InputError(where + "/yaw_deg: allowed: -3600 to 3600");
    if (!(std::abs(key.pose.pitch_deg) <= 90.0)) throw InputError(where + "/pitch_deg: allowed: -90 to 90");
    if (!(key.pose.fov_deg > 0.0 && key.pose.fov_deg < 180.0))
      throw InputError(where + "/fov_deg: allowed: more than 0 and less than 180");
    if (!(key.pose.height_above_ground_m >= 0.0 && key.pose.height_above_ground_m <= 1e6))
      throw InputError(where + "/height_above_ground_m: allowed: 0 to 1e6");
    // Yaw along the shorter way round: unwrap each key to within 180 degrees of the last.
    if (!path.keys_.empty()) {
      const double last = path.keys_.back().pose.yaw_deg;
      key.pose.yaw_deg = last + std::remainder(key.pose.yaw_deg - last, 360.0);
    }
    path.keys_.push_back(key);
  }
  path.hash_ = hex16(fnv1a(j.dump()));
  return path;
}

CameraPose CameraPath::at(double t) const {
  if (t <= keys_.front().time_s) return keys_.front().pose;
  if (t >= keys_.back().time_s) return keys_.back().pose;
  size_t i = 0;
  while (keys_[i + 1].time_s < t) ++i;
  // Catmull-Rom on the non-uniform key times (tangents by finite differences over the neighbours).
  const Key& k1 = keys_[i];
  const Key& k2 = keys_[i + 1];
  const Key& k0 = i > 0 ? keys_[i - 1] : k1;
  const Key& k3 = i + 2 < keys_.size() ? keys_[i + 2] : k2;
  const double h = k2.time_s - k1.time_s;
  const double s = (t - k1.time_s) / h;
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s),
               h11 = s * s * (s - 1);
  auto blend = [&](double CameraPose::*field) {
    const double p1 = k1.pose.*field, p2 = k2.pose.*field;
    const double m1 = &k0 == &k1 ? (p2 - p1) / h : (p2 - k0.pose.*field) / (k2.time_s - k0.time_s);
    const double m2 = &k3 == &k2 ? (p2 - p1) / h : (k3.pose.*field - p1) / (k3.time_s - k1.time_s);
    return h00 * p1 + h10 * h * m1 + h01 * p2 + h11 * h * m2;
  };
  CameraPose p;
  p.yaw_deg = std::fmod(blend(&CameraPose::yaw_deg), 360.0);
  if (p.yaw_deg < 0.0) p.yaw_deg += 360.0;
  p.pitch_deg = std::clamp(blend(&CameraPose::pitch_deg), -90.0, 90.0);
  p.height_above_ground_m = std::max(0.0, blend(&CameraPose::height_above_ground_m));
  p.fov_deg = std::clamp(blend(&CameraPose::fov_deg), 1.0, 179.0);
  return p;
}

}  // namespace firmament::cli
