// `firmament reference SCENE -o OUT.exr`: the CPU reference of a scene's clear sky (spectral, double
// precision, every scattering order; docs/reference.md). Writes the EXR (linear Rec.709, cd/m², the
// GPU image's units), a PNG preview and a stats JSON with the Monte Carlo noise.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "atmosphere/reference_renderer.h"
#include "clouds/reference_clouds.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/log.h"
#include "core/scene.h"
#include "core/tonemap.h"
#include "gpu/context.h"
#include "samples/firmament/command.h"
#include "sky/scene_cloud_medium.h"
#include "sky/scene_view.h"

namespace firmament::cli {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

std::string formatNumber(double v, const char* format = "%.6g") {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

int runReference(const Args& args) {
  const std::string scenePath = args.positionals.at(0);
  std::vector<std::string> overrides = args.all("set");
  if (auto w = args.get("width")) overrides.push_back("/camera/width=" + *w);
  if (auto h = args.get("height")) overrides.push_back("/camera/height=" + *h);

  ReferenceQuality quality;
  quality.samplesPerPixel = args.integer("spp", quality.samplesPerPixel, 0, 1 << 20);
  quality.wavelengthCount = args.integer("wavelengths", quality.wavelengthCount, 3, 471);
  quality.threads = args.integer("threads", 0, 0, 1024);
  quality.seed = uint64_t(args.integer("seed", 1, 0, 2147483647));
  quality.quadratureTolerance = args.number("tolerance", quality.quadratureTolerance);
  if (!(quality.quadratureTolerance > 0.0 && quality.quadratureTolerance < 0.1))
    throw InputError("option --tolerance: must be in (0, 0.1)");

  std::filesystem::path out =
      args.getOr("output", "out/" + std::filesystem::path(scenePath).stem().string() + "_reference.exr");
  if (out.extension() != ".exr") throw InputError("-o " + out.string() + ": the output must end in .exr");
  refuseOverwritingInput(out, scenePath);
  Scene scene = Scene::load(scenePath, overrides);  // InputError (exit 2) on a bad scene or override
  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
    throw InputError("-o " + out.string() + ": cannot create the folder " + folder.string() + ": " + ec.message());
  for (const char* section : {"terrain", "weather"})
    if (scene.hasSection(section))
      logWarning(std::string("reference: the '") + section +
                 "' section is ignored (the reference renders the clear sky)");

  const SceneView view = makeSceneView(scene);
  const ReferenceRenderer renderer(view.atmosphere, view.sunDirection, quality);
  {
    char line[256];
    std::snprintf(line, sizeof(line), "reference: %dx%d, %d spp, %d wavelengths, sun zenith %.3f deg, %d threads",
                  view.camera.width, view.camera.height, quality.samplesPerPixel, quality.wavelengthCount,
                  view.sunZenith / kDegree,
                  quality.threads > 0 ? quality.threads : int(std::max(1u, std::thread::hardware_concurrency())));
    logInfo(line);
  }
  ReferenceImage result;
  {
    Progress progress("reference", uint64_t(view.camera.width) * uint64_t(view.camera.height));
    result = renderReferenceImage(renderer, view.cameraRadius, view.camera,
                                  [&](size_t done, size_t) { progress.set(done); });
  }

  // Clouds (docs/clouds/reference.md): the CPU cloud path tracer over the noise textures baked on
  // the GPU (lavapipe without one) and read back, composited as sky * T + cloud light.
  nlohmann::ordered_json cloudStats;
  if (sceneHasCloudLayers(scene)) {
    const CloudSettings clouds = CloudSettings::fromScene(scene);
    gpu::Context context;
    const double ground = sceneGroundRadius(scene, view);
    // The same weather map as the fast path (sky/scene_weather.h), read with the same sampling.
    const CloudMedium medium = sceneCloudMedium(scene, view, context);
    double middle = 0.0;
    for (const auto& l : clouds.layers) middle += 0.5 * (l.bottom_m + l.top_m) / double(clouds.layers.size());
    const CloudEnvironment environment =
        cloudEnvironmentFromReference(view.atmosphere, view.sunDirection, ground + middle);
    CloudReferenceSettings cloudSettings;
    cloudSettings.samplesPerPixel = args.integer("cloud-spp", cloudSettings.samplesPerPixel, 1, 1 << 20);
    cloudSettings.seed = quality.seed;
    const CloudPathTracer tracer(medium, clouds.lighting, view.atmosphere, view.sunDirection, environment,
                                 cloudSettings);
    CloudReferenceImage cloudImage;
    {
      Progress progress("clouds", uint64_t(view.camera.width) * uint64_t(view.camera.height));
      cloudImage = renderCloudReference(tracer, glm::dvec3(0.0, 0.0, view.cameraRadius), view.camera, quality.threads,
                                        [&](size_t done, size_t) { progress.set(done); });
    }
    for (size_t i = 0; i < result.image.pixelCount(); ++i) {
      const float* c = cloudImage.image.pixels.data() + 4 * i;
      float* p = result.image.pixels.data() + 4 * i;
      for (int k = 0; k < 3; ++k) p[k] = p[k] * c[3] + c[k];
    }
    cloudStats = {{"samples_per_pixel", cloudSettings.samplesPerPixel},
                  {"seconds", cloudImage.seconds},
                  {"scattering_events", cloudImage.events},
                  {"capped_paths", cloudImage.capped},
                  {"environment",
                   "constant sky E_sky/pi from the clear-sky reference at the layers' mid-height; "
                   "constant ground below; no air scattering among the clouds"}};
    result.seconds += cloudImage.seconds;
  }

  Image& image = result.image;
  const std::string sun = formatNumber(view.sunZenith / kDegree) + " " + formatNumber(view.sunAzimuth / kDegree);
  image.metadata["firmament.scene_hash"] = scene.hash();
  image.metadata["firmament.device"] = "cpu reference";
  image.metadata["firmament.units"] = "linear Rec.709, cd/m^2";
  image.metadata["firmament.sun_direction_enu"] = formatNumber(view.sunDirection.x, "%.17g") + " " +
                                                  formatNumber(view.sunDirection.y, "%.17g") + " " +
                                                  formatNumber(view.sunDirection.z, "%.17g");
  image.metadata["firmament.sun"] = "zenith_deg azimuth_deg " + sun;
  image.metadata["firmament.camera"] = scene.at("/camera").dump();
  image.metadata["firmament.reference.spp"] = std::to_string(quality.samplesPerPixel);
  image.metadata["firmament.reference.wavelengths"] = std::to_string(quality.wavelengthCount);
  image.metadata["firmament.reference.seed"] = std::to_string(quality.seed);
  image.metadata["firmament.reference.quadrature_tolerance"] = formatNumber(quality.quadratureTolerance);
  image.metadata["firmament.reference.threads"] = std::to_string(result.threads);
  image.metadata["firmament.timing.reference_s"] = formatNumber(result.seconds, "%.3f");
  image.metadata["firmament.reference.noise_median_relative"] = formatNumber(result.medianRelativeError);
  image.metadata["firmament.reference.noise_p95_relative"] = formatNumber(result.p95RelativeError);
  image.metadata["firmament.reference.noise_max_relative"] = formatNumber(result.maxRelativeError);

  const std::filesystem::path png = std::filesystem::path(out).replace_extension(".png");
  const std::filesystem::path stats = std::filesystem::path(out).replace_extension(".json");
  const ExposureSettings exposure = exposureFromScene(scene);
  writeExr(out, image);
  const double ev100 = writePngPreview(png, image, exposure);

  double sum = 0.0, maxY = 0.0;
  for (double y : result.luminance) sum += y, maxY = std::max(maxY, y);
  const double meanY = result.luminance.empty() ? 0.0 : sum / double(result.luminance.size());
  nlohmann::ordered_json j;
  j["scene"] = scene.source();
  j["scene_hash"] = scene.hash();
  j["device"] = "cpu reference";
  j["width"] = image.width;
  j["height"] = image.height;
  j["sun"] = {
      {"zenith_deg", view.sunZenith / kDegree}, {"azimuth_deg", view.sunAzimuth / kDegree}, {"source", view.sunSource}};
  j["reference"] = {{"samples_per_pixel", quality.samplesPerPixel},
                    {"wavelengths", quality.wavelengthCount},
                    {"wavelength_range_nm", {renderer.wavelengths().front(), renderer.wavelengths().back()}},
                    {"seed", quality.seed},
                    {"quadrature_tolerance", quality.quadratureTolerance},
                    {"path_tolerance", quality.pathTolerance},
                    {"max_bounces", quality.maxBounces},
                    {"roulette_start_bounce", quality.rouletteStartBounce},
                    {"threads", result.threads}};
  j["seconds"] = result.seconds;
  if (!cloudStats.is_null()) j["clouds"] = cloudStats;
  j["luminance_cd_m2"] = {{"mean", meanY}, {"max", maxY}};
  j["noise"] = {{"definition", "Monte Carlo standard error of each pixel's luminance / its luminance"},
                {"median_relative", result.medianRelativeError},
                {"p95_relative", result.p95RelativeError},
                {"max_relative", result.maxRelativeError},
                {"rms_relative", result.rmsRelativeError}};
  j["paths"] = {{"count", result.paths},
                {"mean_events", result.paths ? double(result.events) / double(result.paths) : 0.0},
                {"longest", result.longestPath},
                {"roulette_kills", result.rouletteKills},
                {"capped", result.cappedPaths}};
  j["preview"] = {{"ev100", ev100}, {"tonemap", exposure.tonemap}};
  j["outputs"] = {{"exr", out.string()}, {"png", png.string()}, {"stats", stats.string()}};
  writeTextFileAtomically(stats, j.dump(2) + "\n");

  char summary[320];
  std::snprintf(summary, sizeof(summary),
                "wrote %s (+ .png, EV100 %.2f; + .json) in %.2f s; noise (SE/Y) median %.3g %%, p95 %.3g %%, max "
                "%.3g %%",
                out.string().c_str(), ev100, result.seconds, 100.0 * result.medianRelativeError,
                100.0 * result.p95RelativeError, 100.0 * result.maxRelativeError);
  logInfo(summary);
  return kExitOk;
}

const CommandRegistration registration{Command{
    "reference",
    "CPU reference of a scene's clear sky: spectral, double precision, all orders (EXR + PNG + stats JSON)",
    "reference SCENE [-o OUT.exr] [--width W --height H] [--spp N] [--wavelengths N] [--set /PATH=VALUE]... "
    "[--threads N] [--seed S]",
    {
        {"output", "OUT.exr", "output EXR (default out/<scene>_reference.exr); .png and .json go beside it", false,
         'o'},
        {"width", "W", "image width (same as --set /camera/width=W)"},
        {"height", "H", "image height"},
        {"spp", "N", "Monte Carlo paths per pixel for orders >= 2 (default 256; 0: orders 0 and 1 only)"},
        {"wavelengths", "N", "wavelengths evenly spaced over 360-830 nm (default 48: every 10 nm)"},
        setOption(),
        {"threads", "N", "worker threads (default: all cores); the image does not depend on it"},
        {"seed", "S", "random seed (default 1)"},
        {"tolerance", "T", "relative tolerance of the quadrature of orders 0 and 1 (default 1e-7)"},
        {"cloud-spp", "N", "paths per pixel of the cloud path tracer (scenes with clouds; default 64)"},
    },
    1,
    1,
    runReference,
}};

}  // namespace
}  // namespace firmament::cli
