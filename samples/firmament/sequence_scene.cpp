#include "samples/firmament/sequence_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "firmament/error.h"

namespace firmament::cli {
namespace {

// FNV-1a, 64 bit (Fowler, Noll and Vo; offset basis 14695981039346656037, prime 1099511628211), as 16
// lowercase hex digits: the camera path's identity in a time-lapse's resume manifest.
std::string fnv1aHex(const std::string& bytes) {
  uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char out[17];
  std::snprintf(out, sizeof(out), "%016llx", static_cast<unsigned long long>(hash));
  return out;
}

}  // namespace

CameraPose cameraPoseOf(const Sky& sky) {
  const SkyCamera c = sky.camera();
  return {c.yaw_deg, c.pitch_deg, c.heightAboveGround_m, c.fov_deg};
}

SkyCamera skyCameraOf(const CameraPose& pose, const SkyCamera& base) {
  SkyCamera c = base;
  c.yaw_deg = pose.yaw_deg;
  c.pitch_deg = pose.pitch_deg;
  c.heightAboveGround_m = pose.height_above_ground_m;
  c.fov_deg = pose.fov_deg;
  return c;
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
  path.hash_ = fnv1aHex(j.dump());
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
