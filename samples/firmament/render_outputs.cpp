#include "samples/firmament/render_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/color.h"
#include "core/exr_io.h"
#include "core/tonemap.h"

namespace firmament::cli {
namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
}  // namespace

double writeRenderOutputs(const std::string& exrPath, const Scene& scene, const RenderResult& result,
                          const std::string& deviceDescription, ExposureAdaptation* adaptation, double dtSeconds) {
  namespace fs = std::filesystem;
  fs::path exr(exrPath);
  fs::path png = fs::path(exr).replace_extension(".png");
  fs::path stats = fs::path(exr).replace_extension(".json");

  const ExposureSettings exposure = exposureFromScene(scene);

  writeExr(exr, result.image);
  double adapted = 0.0;
  if (adaptation) adapted = adaptation->update(logAverageLuminance(result.image), dtSeconds, exposure);
  double ev100 = writePngPreview(png, result.image, exposure, adaptation ? &adapted : nullptr);

  // Luminance statistics of the image, for quick checks without opening the EXR.
  const Image& image = result.image;
  double sum = 0.0, maxY = 0.0, logSum = 0.0;
  size_t nonFinite = 0, counted = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = image.pixels.data() + i * size_t(image.channels);
    double y = luminanceRec709(p);
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
  j["scene"] = scene.source();
  j["scene_hash"] = scene.hash();
  j["device"] = deviceDescription;
  j["width"] = image.width;
  j["height"] = image.height;
  j["sun"] = {{"zenith_deg", result.view.sunZenith * kRadToDeg},
              {"azimuth_deg", result.view.sunAzimuth * kRadToDeg},
              {"source", result.view.sunSource},
              {"distance_au", result.view.sunDistanceAu}};
  j["passes"] = nlohmann::json::array();
  for (const auto& t : result.timings) j["passes"].push_back({{"name", t.label}, {"gpu_ms", t.milliseconds}});
  j["precompute_ms"] = result.precomputeMilliseconds;
  j["frame_ms"] = result.frameMilliseconds;
  j["tables"] = result.tablesSource;
  j["spectral_samples"] = result.spectralSamples;
  if (result.clouds.pixelCount() > 0)
    j["clouds"] = {{"view_samples_per_pixel", result.cloudSamples.viewPerPixel},
                   {"light_samples_per_pixel", result.cloudSamples.lightPerPixel},
                   {"reprojected", result.cloudsReprojected},
                   {"noise", result.cloudNoiseSource}};
  if (result.night.run)
    j["night"] = {
        {"sun_altitude_deg", result.night.sunAltitudeDeg}, {"moon_altitude_deg", result.night.moonAltitudeDeg},
        {"light", result.light.moon ? "moon" : "sun"},     {"light_reason", result.light.reason},
        {"sun_ground_lux", result.light.sunGroundLux},     {"moon_ground_lux", result.light.moonGroundLux}};
  if (!result.timingNote.empty()) j["timing_note"] = result.timingNote;
  j["luminance_cd_m2"] = {{"mean", counted ? sum / double(counted) : 0.0},
                          {"max", maxY},
                          {"log_average", counted ? std::exp(logSum / double(counted)) : 0.0}};
  j["non_finite_pixels"] = nonFinite;
  j["preview"] = {{"ev100", ev100}, {"tonemap", exposure.tonemap}};
  if (adaptation) j["preview"]["adapted_luminance_cd_m2"] = adapted;
  j["outputs"] = {{"exr", exr.string()}, {"png", png.string()}, {"stats", stats.string()}};
  writeTextFileAtomically(stats, j.dump(2) + "\n");
  return ev100;
}

}  // namespace firmament::cli
