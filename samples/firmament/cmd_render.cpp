// `firmament render [SCENE] [-o OUT.exr]`: the fast path on the GPU (lavapipe without one). Writes the
// EXR, a PNG preview and a stats JSON beside it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/error.h"
#include "core/log.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "samples/firmament/command.h"
#include "samples/firmament/render_outputs.h"
#include "samples/firmament/sequence_scene.h"
#include "sky/render_plan.h"
#include "sky/sky_renderer.h"

namespace firmament::cli {
namespace {

int runRender(const Args& args) {
  // No scene: the default scene built into the program (the same as scenes/default.json).
  std::string scenePath = args.positionals.empty() ? "scenes/default.json" : args.positionals[0];
  std::vector<std::string> overrides = args.all("set");
  if (auto w = args.get("width")) overrides.push_back("/camera/width=" + *w);
  if (auto h = args.get("height")) overrides.push_back("/camera/height=" + *h);
  Scene scene = args.positionals.empty() ? Scene::parse(defaultSceneText(), kDefaultSceneName, overrides)
                                         : Scene::load(scenePath, overrides);
  SkyRenderOptions options;
  const std::string multipleScattering = args.getOr("multiple-scattering", "fms");
  if (multipleScattering == "tables") {
    options.multipleScattering = MultipleScattering::BrunetonTables;
  } else if (multipleScattering != "fms") {
    throw InputError("--multiple-scattering " + multipleScattering + ": allowed: fms, tables");
  }
  options.tables.scatteringOrders = args.integer("orders", options.tables.scatteringOrders, 1, 64);
  options.viewSteps = args.integer("view-steps", options.viewSteps, 1, 4096);
  if (args.getOr("spectral-samples", "auto") != "auto") {
    options.luts.spectralSamples = args.integer("spectral-samples", 3, 3, 48);
    if (options.luts.spectralSamples % 3 != 0)
      throw InputError("--spectral-samples " + std::to_string(options.luts.spectralSamples) +
                       ": allowed: auto, 3 (three wavelengths) or a multiple of 3 from 6 to 48");
  }
  std::string method = args.getOr("sky", "lut");
  if (method == "lut") {
    options.method = SkyMethod::SkyViewLut;
  } else if (method == "march") {
    options.method = SkyMethod::PerPixel;
  } else {
    throw InputError("--sky " + method + ": allowed: lut (sky-view table), march (every pixel)");
  }

  if (auto size = args.get("aerial-volume")) {
    // CxRxN: froxel columns, rows, depth slices of the aerial-perspective volume.
    int c = 0, r = 0, n = 0;
    char x1 = 0, x2 = 0;
    char tail = 0;
    if (std::sscanf(size->c_str(), "%d%c%d%c%d%c", &c, &x1, &r, &x2, &n, &tail) != 5 || x1 != 'x' || x2 != 'x' ||
        c < 2 || r < 2 || n < 2 || c > 1024 || r > 1024 || n > 1024)
      throw InputError("--aerial-volume " + *size + ": allowed: CxRxN with each of C, R, N in 2..1024, e.g. 32x32x32");
    options.aerialPerspective.columns = c;
    options.aerialPerspective.rows = r;
    options.aerialPerspective.slices = n;
  }
  options.aerialPerspective.maxDistance_m = args.number("aerial-volume-depth", 0.0);
  if (!(options.aerialPerspective.maxDistance_m >= 0.0) || options.aerialPerspective.maxDistance_m > 1e7)
    throw InputError("--aerial-volume-depth: allowed: 0 (the clouds' march limit) or a distance in metres up to 1e7");

  RenderPlan plan = planRender(scene, planOptions(options));
  if (args.has("explain")) {
    std::printf("%s: %dx%d\n%s", scene.source().c_str(), int(scene.integer("/camera/width")),
                int(scene.integer("/camera/height")), describePlan(plan).c_str());
    if (!args.has("output")) return kExitOk;
  }
  for (const auto& u : plan.unavailable) logWarning(u.name + ": " + u.reason);

  std::filesystem::path out = args.getOr("output", "out/" + std::filesystem::path(scenePath).stem().string() + ".exr");
  if (out.extension() != ".exr") throw InputError("-o " + out.string() + ": the output must end in .exr");
  std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
    throw InputError("-o " + out.string() + ": cannot create the folder " + folder.string() + ": " + ec.message());

  // A sequence: frame i moves the camera and the clouds' clock by i times the rates; each frame
  // continues the previous one (temporal reprojection, /clouds/temporal_update) and is written as
  // OUT_NNNN.exr.
  const int frames = args.integer("frames", 1, 1, 100000);
  const double interval = args.number("frame-interval", 1.0 / 30.0);
  if (!(interval >= 0.0) || interval > 86400.0)
    throw InputError("--frame-interval " + std::to_string(interval) + ": allowed: 0 to 86400 s");
  const double yawRate = args.number("yaw-rate", 0.0), pitchRate = args.number("pitch-rate", 0.0);
  const double climbRate = args.number("climb-rate", 0.0);
  for (double rate : {yawRate, pitchRate, climbRate})
    if (!std::isfinite(rate)) throw InputError("--yaw-rate, --pitch-rate, --climb-rate: allowed: finite numbers");
  if (frames == 1 &&
      (args.has("yaw-rate") || args.has("pitch-rate") || args.has("climb-rate") || args.has("frame-interval")))
    throw InputError(
        "--yaw-rate, --pitch-rate, --climb-rate and --frame-interval describe a sequence: give --frames N (N > 1)");
  const SequenceSceneSource source{args.positionals.empty() ? std::string() : scenePath, overrides};
  auto frameScene = [&](int i) {
    if (i == 0) return scene;
    const double t = double(i) * interval;
    CameraPose pose = cameraPoseOf(scene);
    pose.yaw_deg = std::fmod(pose.yaw_deg + yawRate * t, 360.0);
    pose.pitch_deg += pitchRate * t;
    if (pose.pitch_deg < -90.0 || pose.pitch_deg > 90.0)
      throw InputError("--pitch-rate: frame " + std::to_string(i) + " would pitch to " +
                       std::to_string(pose.pitch_deg) + " deg; allowed: -90 to 90");
    pose.height_above_ground_m += climbRate * t;
    return sequenceFrameScene(source, scene, t, pose);
  };
  auto framePath = [&](int i) {
    if (frames == 1) return out;
    char suffix[32];
    std::snprintf(suffix, sizeof(suffix), "_%04d.exr", i);
    return std::filesystem::path(out).replace_extension("").concat(suffix);
  };
  for (int i = 1; i < frames; ++i) frameScene(i);  // bad rates fail before anything is written
  // No output may replace the scene file (OUT.json is the stats beside OUT.exr).
  if (!args.positionals.empty())
    for (int i = 0; i < frames; ++i) refuseOverwritingInput(framePath(i), scenePath);

  // Phases: device, then render (tables + frame) and write per frame. The bar appears only past one second.
  auto progress = std::make_unique<Progress>("render", 1 + 2 * frames);
  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  gpu::Context context(contextOptions);
  logInfo("device: " + context.description());
  SkyRenderer renderer(context);
  progress->advance();
  RenderResult result;
  double ev100 = 0.0;
  ExposureAdaptation adaptation;  // the auto exposure's state through a sequence
  for (int i = 0; i < frames; ++i) {
    const Scene current = frameScene(i);
    options.continueSequence = i > 0;
    result = renderer.render(current, options);
    progress->advance();
    ev100 = writeRenderOutputs(framePath(i).string(), current, result, context.description(),
                               frames > 1 ? &adaptation : nullptr, i > 0 ? interval : 0.0);
    progress->advance();
    if (frames > 1) {
      char line[200];
      std::snprintf(line, sizeof(line), "  frame %4d: %9.3f ms%s", i, result.frameMilliseconds,
                    result.clouds.pixelCount() == 0 ? ""
                    : result.cloudsReprojected      ? ", clouds reprojected"
                                                    : ", clouds marched in full");
      logInfo(line);
    }
  }
  progress.reset();  // ends the bar's line before the summary
  out = framePath(frames - 1);

  for (const auto& t : result.timings) {
    char line[160];
    std::snprintf(line, sizeof(line), "  %-36s %9.3f ms", t.label.c_str(), t.milliseconds);
    logInfo(line);
  }
  char summary[256];
  std::snprintf(summary, sizeof(summary), "wrote %s (+ .png, EV100 %.2f; + .json); sun zenith %.3f deg", out.c_str(),
                ev100, result.view.sunZenith * 180.0 / 3.14159265358979323846);
  logInfo(summary);
  return kExitOk;
}

const CommandRegistration reg{
    {"render",
     "render a scene with the fast GPU path: EXR + PNG preview + stats JSON",
     "render [SCENE] [-o OUT.exr] [--width W --height H] [--set /PATH=VALUE]... "
     "[--multiple-scattering fms|tables] [--orders N] [--spectral-samples auto|N] [--sky lut|march] "
     "[--aerial-volume CxRxN] [--aerial-volume-depth M] [--frames N [--frame-interval S] "
     "[--yaw-rate DEG/S] [--pitch-rate DEG/S] [--climb-rate M/S]] [--explain] [--device D]",
     {{"output", "OUT.exr", "output EXR (default out/<scene>.exr); .png and .json go beside it", false, 'o'},
      {"width", "W", "image width (same as --set /camera/width=W)"},
      {"height", "H", "image height"},
      setOption(),
      {"explain", "",
       "print the passes this scene needs (and those it leaves out); "
       "with -o also render"},
      {"view-steps", "N", "march steps per view ray (quality knob, default 32)"},
      {"sky", "lut|march", "sky-view table read per pixel (default) or a march per pixel"},
      {"spectral-samples", "N",
       "wavelengths: auto (default: 3, or 12 with the sun within 15 deg of the horizon or below), 3, or 6..48 "
       "integrated to luminance"},
      {"multiple-scattering", "fms|tables",
       "fms: Hillaire 2020's f_ms table and a march (default); tables: Bruneton 2017's "
       "4D tables of N orders"},
      {"orders", "N", "scattering orders of the 4D tables (default 4)"},
      {"aerial-volume", "CxRxN",
       "aerial-perspective volume read by the clouds (/clouds/aerial_perspective volume): froxel "
       "columns x rows x depth slices (default 32x32x32)"},
      {"aerial-volume-depth", "M", "distance its slices reach, m (default 0: the clouds' march limit, 80 km)"},
      {"frames", "N",
       "render a sequence of N frames (OUT_0000.exr ...), each continuing the last "
       "(clouds: temporal reprojection, /clouds/temporal_update)"},
      {"frame-interval", "S",
       "seconds between frames: the clouds' clock and, without a sun section, /time/utc (the sun) advance by it "
       "(default 1/30)"},
      {"yaw-rate", "DEG/S", "camera turn rate in a sequence (clockwise from above)"},
      {"pitch-rate", "DEG/S", "camera pitch rate in a sequence"},
      {"climb-rate", "M/S", "camera climb rate in a sequence"},
      deviceOption()},
     0,
     1,
     runRender}};

}  // namespace
}  // namespace firmament::cli
