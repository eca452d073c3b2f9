// `firmament render [SCENE] [-o OUT.exr]`: the fast path on the GPU (lavapipe without one). Writes the
// EXR, a PNG preview and a stats JSON beside it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "firmament/image.h"
#include "firmament/sky.h"
#include "samples/firmament/command.h"
#include "samples/firmament/render_outputs.h"
#include "samples/firmament/sequence_scene.h"

namespace firmament::cli {
namespace {

int runRender(const Args& args) {
  // No scene: the default scene built into the program (the same as scenes/default.json).
  std::string scenePath = args.positionals.empty() ? "scenes/default.json" : args.positionals[0];
  std::vector<std::string> overrides = args.all("set");
  if (auto w = args.get("width")) overrides.push_back("/camera/width=" + *w);
  if (auto h = args.get("height")) overrides.push_back("/camera/height=" + *h);
  Sky::Builder builder;
  if (!args.positionals.empty()) builder.sceneFile(scenePath);
  for (const std::string& o : overrides) builder.set(o);
  builder.device(args.getOr("device", ""));

  // The quality knobs (firmament::qualityKnobs()), each from its option.
  const std::string multipleScattering = args.getOr("multiple-scattering", "auto");
  if (multipleScattering != "tables" && multipleScattering != "fms" && multipleScattering != "auto")
    throw InputError("--multiple-scattering " + multipleScattering + ": allowed: auto, fms, tables");
  builder.quality("/atmosphere/multiple_scattering=" + multipleScattering);
  if (args.has("orders"))
    builder.quality("/atmosphere/scattering_orders=" + std::to_string(args.integer("orders", 4, 1, 64)));
  if (args.has("view-steps"))
    builder.quality("/atmosphere/view_steps=" + std::to_string(args.integer("view-steps", 32, 1, 4096)));
  if (args.getOr("spectral-samples", "auto") != "auto") {
    const int samples = args.integer("spectral-samples", 3, 3, 48);
    if (samples % 3 != 0)
      throw InputError("--spectral-samples " + std::to_string(samples) +
                       ": allowed: auto, 3 (three wavelengths) or a multiple of 3 from 6 to 48");
    builder.quality("/atmosphere/spectral_samples=" + std::to_string(samples));
  }
  std::string method = args.getOr("sky", "lut");
  if (method != "lut" && method != "march")
    throw InputError("--sky " + method + ": allowed: lut (sky-view table), march (every pixel)");
  builder.quality("/atmosphere/sky=" + method);

  if (auto size = args.get("aerial-volume")) {
    // CxRxN: froxel columns, rows, depth slices of the aerial-perspective volume.
    int c = 0, r = 0, n = 0;
    char x1 = 0, x2 = 0;
    char tail = 0;
    if (std::sscanf(size->c_str(), "%d%c%d%c%d%c", &c, &x1, &r, &x2, &n, &tail) != 5 || x1 != 'x' || x2 != 'x' ||
        c < 2 || r < 2 || n < 2 || c > 1024 || r > 1024 || n > 1024)
      throw InputError("--aerial-volume " + *size + ": allowed: CxRxN with each of C, R, N in 2..1024, e.g. 32x32x32");
    builder.quality("/aerial_perspective/columns=" + std::to_string(c));
    builder.quality("/aerial_perspective/rows=" + std::to_string(r));
    builder.quality("/aerial_perspective/slices=" + std::to_string(n));
  }
  const double aerialDepth = args.number("aerial-volume-depth", 0.0);
  if (!(aerialDepth >= 0.0) || aerialDepth > 1e7)
    throw InputError("--aerial-volume-depth: allowed: 0 (the clouds' march limit) or a distance in metres up to 1e7");
  if (args.has("aerial-volume-depth"))
    builder.quality("/aerial_perspective/depth_m=" + formatNumber("%.17g", aerialDepth));
  // The clouds' sub-frames of a still (/clouds/march/still_samples); given, they apply to every frame.
  if (auto n = args.get("still-samples")) builder.quality("/clouds/march/still_samples=" + *n);

  const SkyPlan plan = builder.explain();
  if (args.has("explain")) {
    std::printf("%s: %dx%d\n%s", plan.scene.c_str(), plan.width, plan.height, plan.text.c_str());
    if (!args.has("output")) return kExitOk;
  }
  for (const auto& u : plan.unavailable) warn(u.name + ": " + u.reason);

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
  auto framePath = [&](int i) {
    if (frames == 1) return out;
    char suffix[32];
    std::snprintf(suffix, sizeof(suffix), "_%04d.exr", i);
    return std::filesystem::path(out).replace_extension("").concat(suffix);
  };
  // No output may replace the scene file (OUT.json is the stats beside OUT.exr).
  if (!args.positionals.empty())
    for (int i = 0; i < frames; ++i) refuseOverwritingInput(framePath(i), scenePath);

  // Phases: device, then render (tables + frame) and write per frame. The bar appears only past one second.
  auto progress = std::make_unique<ProgressBar>("render", 1 + 2 * frames);
  // One frame is a still (the clouds average their sub-frames); more continue each other.
  builder.temporalReprojection(frames > 1);
  std::unique_ptr<Sky> sky = builder.build();
  info("device: " + sky->deviceDescription());
  progress->advance();

  // Frame i's camera: the built one moved by i times the rates.
  const SkyCamera camera = sky->camera();
  auto frameCamera = [&](int i) {
    const double t = double(i) * interval;
    CameraPose pose = cameraPoseOf(*sky);
    pose.yaw_deg = std::fmod(camera.yaw_deg + yawRate * t, 360.0);
    pose.pitch_deg = camera.pitch_deg + pitchRate * t;
    if (pose.pitch_deg < -90.0 || pose.pitch_deg > 90.0)
      throw InputError("--pitch-rate: frame " + std::to_string(i) + " would pitch to " +
                       std::to_string(pose.pitch_deg) + " deg; allowed: -90 to 90");
    pose.height_above_ground_m = camera.heightAboveGround_m + climbRate * t;
    pose.fov_deg = camera.fov_deg;
    return skyCameraOf(pose, camera);
  };
  for (int i = 1; i < frames; ++i)  // bad rates fail before anything is written
    sky->checkSequenceFrame(double(i) * interval, frameCamera(i));

  SkyFrame frame;
  double ev100 = 0.0;
  EyeAdaptation adaptation;  // the auto exposure's state through a sequence
  for (int i = 0; i < frames; ++i) {
    if (i > 0) sky->setSequenceFrame(double(i) * interval, frameCamera(i));
    frame = sky->render(plan.width, plan.height);
    progress->advance();
    ev100 = writeRenderOutputs(framePath(i).string(), frame, Exposure(*sky), sky->deviceDescription(),
                               frames > 1 ? &adaptation : nullptr, i > 0 ? interval : 0.0);
    progress->advance();
    if (frames > 1) {
      char line[200];
      std::snprintf(line, sizeof(line), "  frame %4d: %9.3f ms%s", i, frame.gpuMilliseconds,
                    !frame.clouds.rendered    ? ""
                    : frame.cloudsReprojected ? ", clouds reprojected"
                                              : ", clouds marched in full");
      info(line);
    }
  }
  progress.reset();  // ends the bar's line before the summary
  out = framePath(frames - 1);

  for (const auto& t : frame.passes) {
    char line[160];
    std::snprintf(line, sizeof(line), "  %-36s %9.3f ms", t.label.c_str(), t.milliseconds);
    info(line);
  }
  char summary[256];
  std::snprintf(summary, sizeof(summary), "wrote %s (+ .png, EV100 %.2f; + .json); sun zenith %.3f deg", out.c_str(),
                ev100, frame.sunZenith_deg);
  info(summary);
  return kExitOk;
}

const CommandRegistration reg{
    {"render",
     "render a scene with the fast GPU path: EXR + PNG preview + stats JSON",
     "render [SCENE] [-o OUT.exr] [--width W --height H] [--set /PATH=VALUE]... "
     "[--multiple-scattering auto|fms|tables] [--orders N] [--spectral-samples auto|N] [--sky lut|march] "
     "[--aerial-volume CxRxN] [--aerial-volume-depth M] [--still-samples N] [--frames N [--frame-interval S] "
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
      {"multiple-scattering", "auto|fms|tables",
       "auto (default): f_ms with the sun up, Bruneton 2017's 4D tables in twilight (blended from -2 to -6 deg; "
       "f_ms always with clouds or terrain); fms: Hillaire 2020's f_ms table and a march; tables: the 4D tables "
       "of N orders"},
      {"orders", "N", "scattering orders of the 4D tables (default 4)"},
      {"aerial-volume", "CxRxN",
       "aerial-perspective volume read by the clouds (/clouds/aerial_perspective volume): froxel "
       "columns x rows x depth slices (default 32x32x32)"},
      {"aerial-volume-depth", "M", "distance its slices reach, m (default 0: the clouds' march limit, 80 km)"},
      {"still-samples", "N",
       "clouds: jittered sub-frames a still averages (1..64; default: /clouds/march/still_samples); given, every "
       "frame of --frames takes them too"},
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
