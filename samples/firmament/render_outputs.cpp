#include "samples/firmament/render_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "samples/firmament/command.h"

namespace firmament::cli {

double writeRenderOutputs(const std::string& exrPath, const SkyFrame& frame, const Exposure& exposure,
                          const std::string& deviceDescription, EyeAdaptation* adaptation, double dtSeconds) {
  namespace fs = std::filesystem;
  fs::path exr(exrPath);
  fs::path png = fs::path(exr).replace_extension(".png");
  fs::path stats = fs::path(exr).replace_extension(".json");

  saveExr(frame, exr.string());
  double adapted = 0.0;
  if (adaptation) adapted = adaptation->update(logAverageLuminance(frame), dtSeconds, exposure);
  double ev100 = exposure.savePng(frame, png.string(), adaptation ? &adapted : nullptr);

  // Luminance statistics of the image, for quick checks without opening the EXR. Luminance of linear
  // Rec.709: ITU-R BT.709-6, item 3.2 (the Y row of the RGB to XYZ matrix for D65).
  double sum = 0.0, maxY = 0.0, logSum = 0.0;
  size_t nonFinite = 0, counted = 0;
  const size_t pixels = size_t(frame.width) * size_t(frame.height);
  for (size_t i = 0; i < pixels; ++i) {
    const float* p = frame.rgba.data() + i * 4;
    const double y = 0.2126 * double(p[0]) + 0.7152 * double(p[1]) + 0.0722 * double(p[2]);
    if (!std::isfinite(y)) {
      ++nonFinite;
      continue;
    }
    sum += y;
    maxY = std::max(maxY, y);
    logSum += std::log(std::max(y, 1e-6));
    ++counted;
  }
  nlohmann::json j;
  j["scene"] = frame.scene;
  j["scene_hash"] = frame.sceneHash;
  j["device"] = deviceDescription;
  j["width"] = frame.width;
  j["height"] = frame.height;
  j["sun"] = {{"zenith_deg", frame.sunZenith_deg},
              {"azimuth_deg", frame.sunAzimuth_deg},
              {"source", frame.sunSource},
              {"distance_au", frame.sunDistance_au}};
  j["passes"] = nlohmann::json::array();
  for (const auto& t : frame.passes) j["passes"].push_back({{"name", t.label}, {"gpu_ms", t.milliseconds}});
  j["precompute_ms"] = frame.precomputeMilliseconds;
  j["frame_ms"] = frame.gpuMilliseconds;
  j["tables"] = frame.tablesSource;
  j["spectral_samples"] = frame.spectralSamples;
  if (frame.clouds.rendered)
    j["clouds"] = {{"view_samples_per_pixel", frame.clouds.viewSamplesPerPixel},
                   {"light_samples_per_pixel", frame.clouds.lightSamplesPerPixel},
                   {"reprojected", frame.cloudsReprojected},
                   {"noise", frame.clouds.noiseSource}};
  if (frame.night.run)
    j["night"] = {
        {"sun_altitude_deg", frame.night.sunAltitude_deg},      {"moon_altitude_deg", frame.night.moonAltitude_deg},
        {"light", frame.night.moonIsTheLight ? "moon" : "sun"}, {"light_reason", frame.night.lightReason},
        {"sun_ground_lux", frame.night.sunGroundLux},           {"moon_ground_lux", frame.night.moonGroundLux}};
  if (!frame.timingNote.empty()) j["timing_note"] = frame.timingNote;
  j["luminance_cd_m2"] = {{"mean", counted ? sum / double(counted) : 0.0},
                          {"max", maxY},
                          {"log_average", counted ? std::exp(logSum / double(counted)) : 0.0}};
  j["non_finite_pixels"] = nonFinite;
  j["preview"] = {{"ev100", ev100}, {"tonemap", exposure.toneMap()}};
  if (adaptation) j["preview"]["adapted_luminance_cd_m2"] = adapted;
  j["outputs"] = {{"exr", exr.string()}, {"png", png.string()}, {"stats", stats.string()}};
  writeTextAtomically(stats, j.dump(2) + "\n");
  return ev100;
}

}  // namespace firmament::cli
