// `firmament bench atmosphere|clouds|terrain|night|weather|all --out DIR [--quick]`: error-against-run-time sweeps
// (docs/bench.md). Each target is one entry of kTargets; the ones not written yet exit 2.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/log.h"
#include "eval/atmosphere_bench.h"
#include "eval/cloud_bench.h"
#include "eval/cloud_calibration.h"
#include "eval/night_bench.h"
#include "eval/terrain_bench.h"
#include "eval/weather_bench.h"
#include "gpu/context.h"
#include "samples/firmament/command.h"

namespace firmament::cli {
namespace {

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  if (!(in >> a >> b >> c)) return "";
  char text[96];
  std::snprintf(text, sizeof(text), "%.2f %.2f %.2f", a, b, c);
  return text;
}

// The note a report carries about the machine's load before and after a run ("" when unknown).
std::string loadNote(const std::string& before) {
  if (before.empty()) return "";
  return "Load average (1, 5, 15 min) before: " + before + "; after: " + loadAverage() +
         " (timings on a shared machine are noisy).";
}

// --timing-size WxH into width and height (kept when the option is absent); `example` goes into the error.
void readTimingSize(const Args& args, int& width, int& height, const std::string& example) {
  const auto size = args.get("timing-size");
  if (!size) return;
  int w = 0, h = 0;
  char x = 0, tail = 0;
  if (std::sscanf(size->c_str(), "%d%c%d%c", &w, &x, &h, &tail) != 3 || x != 'x' || w < 8 || h < 8 || w > 8192 ||
      h > 8192)
    throw InputError("--timing-size " + *size + ": allowed: WxH with W and H in 8..8192, e.g. " + example);
  width = w;
  height = h;
}

int benchAtmosphere(const Args& args, const std::filesystem::path& out) {
  AtmosphereBenchConfig config;
  config.quick = args.has("quick");
  config.outDir = out;
  config.scenarios = atmosphereBenchScenarios(config.quick);
  config.knobs = atmosphereBenchKnobs(config.quick);
  config.repeats = args.integer("repeats", 3, 1, 100);
  config.referenceQuality.threads = args.integer("threads", 0, 0, 1024);
  if (auto only = args.get("scenario")) {
    std::vector<BenchScenario> kept;
    for (const auto& s : config.scenarios)
      if (s.name == *only) kept.push_back(s);
    if (kept.empty())
      throw InputError("--scenario " + *only +
                       ": no such scenario (noon, sunset, twilight, altitude_10km, limb_100km)");
    config.scenarios = kept;
  }
  if (auto spp = args.get("reference-spp")) {
    const int n = args.integer("reference-spp", 0, 1, 1 << 20);
    for (auto& s : config.scenarios) s.referenceSamples = n;
  }

  // No pipeline or table cache on disk: precompute_ms must measure the tables being computed.
  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  contextOptions.persistentPipelineCache = false;
  gpu::Context context(contextOptions);
  logInfo("bench atmosphere: device " + context.description() + ", output " + out.string());
  const std::string loadBefore = loadAverage();
  AtmosphereBenchResult result = runAtmosphereBench(context, config);
  const std::string loadAfter = loadAverage();
  if (!loadBefore.empty())
    config.environmentNote = "Load average (1, 5, 15 min) before: " + loadBefore + "; after: " + loadAfter +
                             " (timings on a shared machine are noisy).";
  writeAtmosphereBenchOutputs(config, result);
  for (const auto& r : result.rows)
    if (r.knob == "default") {
      char line[200];
      std::snprintf(line, sizeof(line), "default %-14s rel_rmse %.4g  PSNR %.2f dB  tables %.2f ms  frame %.2f ms",
                    r.scenario.c_str(), r.relRmse, r.psnrDb, r.precomputeMs, r.frameMs);
      logInfo(line);
    }
  for (const auto& f : result.fullFrame) {
    char line[160];
    std::snprintf(line, sizeof(line), "%dx%d frame (%s): %.2f ms", f.width, f.height, f.method.c_str(), f.frameMs);
    logInfo(line);
  }
  logInfo("wrote " + (out / "results.csv").string() + ", " + (out / "report.md").string() + " and plots in " +
          std::to_string(int(result.seconds)) + " s");
  return kExitOk;
}

// `bench clouds --calibrate`: fit the octave parameters to the path tracer (eval/cloud_calibration.h).
int calibrateClouds(const Args& args, const std::filesystem::path& out) {
  if (args.has("timing-only")) throw InputError("--timing-only: not with --calibrate (a calibration times nothing)");
  CloudCalibrationConfig config;
  config.quick = args.has("quick");
  config.outDir = out;
  config.threads = args.integer("threads", 0, 0, 1024);
  config.samplesPerPixel = args.integer("reference-spp", 0, 0, 1 << 20);
  config.octaves = args.integer("octaves", 3, 1, 8);
  config.lightSteps = args.integer("light-steps", 0, 1, 64);
  config.evaluateDefaults = args.has("evaluate-defaults");
  config.images = args.has("images");
  config.lowSunOnly = args.has("low-sun");
  if (config.lowSunOnly && (args.has("reflection-only") || args.has("evaluate-defaults")))
    throw InputError(
        "--low-sun: not with --reflection-only or --evaluate-defaults (it fits mu_0 alone, the rest at the shipped "
        "fit)");
  config.reflection = args.has("reflection") || args.has("reflection-only") || config.lowSunOnly;
  config.reflectionOnly = args.has("reflection-only");
  if (config.reflection) config.maxEvaluations = 150;  // six dimensions instead of four
  config.group = args.getOr("group", "");
  config.phase = args.getOr("phase", config.phase);
  checkCloudCalibrationConfig(config);  // refused before any work
  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  gpu::Context context(contextOptions);
  logInfo("calibrate clouds: device " + context.description() + ", output " + out.string());
  const std::string loadBefore = loadAverage();
  const CloudCalibrationResult result = runCloudCalibration(context, config);
  if (!loadBefore.empty())
    config.environmentNote = "Load average (1, 5, 15 min) before: " + loadBefore + "; after: " + loadAverage() + ".";
  writeCloudCalibrationOutputs(config, result);
  logInfo("wrote " + (out / "clouds_calibration.csv").string() + " and " + (out / "clouds_calibration.md").string());
  return kExitOk;
}

int benchClouds(const Args& args, const std::filesystem::path& out) {
  if (args.has("calibrate")) return calibrateClouds(args, out);
  CloudBenchConfig config;
  config.quick = args.has("quick");
  config.outDir = out;
  config.repeats = args.integer("repeats", 3, 1, 100);
  config.threads = args.integer("threads", 0, 0, 1024);
  config.samplesPerPixel = args.integer("reference-spp", 0, 1, 1 << 20);
  config.scenario = args.getOr("scenario", "");
  config.images = args.has("images");
  config.timingOnly = args.has("timing-only");
  config.timingSetting = args.getOr("timing-setting", "");
  config.errorSetting = args.getOr("error-setting", "");
  readTimingSize(args, config.timingWidth, config.timingHeight, "1920x1080");  // the frame timing's image size
  checkCloudBenchConfig(config);                                               // refused before any work
  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  gpu::Context context(contextOptions);
  logInfo("bench clouds: device " + context.description() + ", output " + out.string());
  const std::string loadBefore = loadAverage();
  auto noteLoad = [&] { config.environmentNote = loadNote(loadBefore); };
  if (!config.timingOnly) {
    const std::vector<CloudBenchRow> rows = runCloudBench(context, config);
    noteLoad();
    writeCloudBenchOutputs(config, rows);
    logInfo("wrote " + (out / "clouds_results.csv").string() + " and " + (out / "clouds_report.md").string());
  }
  if (!config.errorSetting.empty()) return kExitOk;  // the chosen error rows only: no timing sweep
  const std::vector<CloudTimingRow> timing = runCloudTiming(context, config);
  if (config.timingOnly) noteLoad();
  writeCloudTimingOutputs(config, timing);
  logInfo("wrote " + (out / "clouds_timing.csv").string() + " and " + (out / "clouds_timing.md").string());
  return kExitOk;
}

int benchTerrain(const Args& args, const std::filesystem::path& out) {
  TerrainBenchConfig config;
  config.quick = args.has("quick");
  config.outDir = out;
  config.repeats = args.integer("repeats", 3, 1, 100);
  config.threads = args.integer("threads", 0, 0, 1024);
  config.skyDirections = args.integer("reference-spp", 0, 1, 1 << 16);
  config.scenario = args.getOr("scenario", "");
  config.demDir = args.getOr("dem-dir", config.demDir.string());
  if (config.quick) config.timingWidth = 160, config.timingHeight = 90;
  readTimingSize(args, config.timingWidth, config.timingHeight, "640x360");
  checkTerrainBenchConfig(config);  // refused before any work
  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  gpu::Context context(contextOptions);
  logInfo("bench terrain: device " + context.description() + ", output " + out.string());
  const std::string loadBefore = loadAverage();
  const std::vector<TerrainBenchRow> rows = runTerrainBench(context, config);
  config.environmentNote = loadNote(loadBefore);
  writeTerrainBenchOutputs(config, rows, context.description());
  logInfo("wrote " + (out / "terrain_results.csv").string() + " and " + (out / "terrain_report.md").string());
  return kExitOk;
}

int benchWeather(const Args& args, const std::filesystem::path& out) {
  WeatherBenchConfig config;
  config.quick = args.has("quick");
  config.outDir = out;
  if (const auto preset = args.get("scenario")) config.presets = {*preset};
  checkWeatherBenchConfig(config);  // refused before any work
  const std::string loadBefore = loadAverage();
  const std::vector<WeatherBenchRow> rows = runWeatherBench(config);
  config.environmentNote = loadNote(loadBefore);
  writeWeatherBenchOutputs(config, rows);
  logInfo("wrote " + (out / "weather_results.csv").string() + " and " + (out / "weather_report.md").string());
  return kExitOk;
}

int benchNight(const Args& args, const std::filesystem::path& out) {
  NightBenchConfig config;
  config.quick = args.has("quick");
  config.outDir = out;
  config.repeats = args.integer("repeats", 3, 1, 100);
  config.threads = args.integer("threads", 0, 0, 1024);
  config.referenceSpp = args.integer("reference-spp", 0, 1, 1 << 16);
  config.term = args.getOr("scenario", "");
  // Repeatable: each --sun-altitude and --table-orders adds one value (checked with the config below).
  auto numbers = [&](const char* name) {
    std::vector<double> values;
    for (const std::string& text : args.all(name)) {
      char* end = nullptr;
      const double d = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !std::isfinite(d))
        throw InputError(std::string("option --") + name + ": '" + text + "' is not a number");
      values.push_back(d);
    }
    return values;
  };
  if (args.has("sun-altitude")) config.twilightAltitudesDeg = numbers("sun-altitude");
  if (args.has("table-orders")) {
    config.twilightTableOrders.clear();
    for (double n : numbers("table-orders")) {
      if (n != std::floor(n)) throw InputError("option --table-orders: '" + std::to_string(n) + "' is not an integer");
      config.twilightTableOrders.push_back(int(n));
    }
  }
  if (config.quick) config.timingWidth = 160, config.timingHeight = 90;
  readTimingSize(args, config.timingWidth, config.timingHeight, "640x360");
  checkNightBenchConfig(config);  // refused before any work
  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  gpu::Context context(contextOptions);
  logInfo("bench night: device " + context.description() + ", output " + out.string());
  const std::string loadBefore = loadAverage();
  const std::vector<NightBenchRow> rows = runNightBench(context, config);
  config.environmentNote = loadNote(loadBefore);
  writeNightBenchOutputs(config, rows, context.description());
  logInfo("wrote " + (out / "night_results.csv").string() + " and " + (out / "night_report.md").string());
  return kExitOk;
}

struct Target {
  std::string name;
  std::function<int(const Args&, const std::filesystem::path&)> run;
};

const std::vector<Target>& targets() {
  static const std::vector<Target> t = {{"atmosphere", benchAtmosphere},
                                        {"clouds", benchClouds},
                                        {"terrain", benchTerrain},
                                        {"night", benchNight},
                                        {"weather", benchWeather}};
  return t;
}

int runBench(const Args& args) {
  const std::string what = args.positionals.at(0);
  const auto outOption = args.get("out");
  if (!outOption) throw InputError("firmament bench: --out DIR is required");
  const std::filesystem::path out = *outOption;

  std::vector<const Target*> selected;
  for (const auto& t : targets())
    if (t.name == what || what == "all") selected.push_back(&t);
  if (selected.empty()) {
    std::string names;
    for (const auto& t : targets()) names += t.name + "|";
    throw InputError("firmament bench: unknown target '" + what + "' (" + names + "all)");
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError("--out " + out.string() + ": cannot create the folder: " + ec.message());
  for (const Target* t : selected)
    if (int code = t->run(args, out); code != kExitOk) return code;
  return kExitOk;
}

const CommandRegistration registration{Command{
    "bench",
    "error-against-run-time sweeps of the quality knobs: results.csv, report.md, SVG plots (docs/bench.md)",
    "bench atmosphere|clouds|terrain|night|weather|all --out DIR [--quick] [--scenario NAME] [--repeats N] "
    "[--reference-spp "
    "N] [--sun-altitude DEG]... [--table-orders N]... "
    "[--images] [--timing-only] [--timing-size WxH] [--timing-setting TEXT] [--error-setting TEXT] [--calibrate "
    "[--octaves N] [--light-steps N] [--phase P] [--group G] [--evaluate-defaults] "
    "[--reflection|--reflection-only|--low-sun]] [--device D]",
    {
        {"out", "DIR", "output folder (created); reference images are cached in DIR/references"},
        {"quick", "", "smaller images, fewer knob values, noisier references: under 2 minutes on 2 cores"},
        {"scenario", "NAME",
         "only this scenario (atmosphere: noon, sunset, twilight, altitude_10km, limb_100km; clouds: "
         "cumulus_noon, stratocumulus_sunset, overcast, cumulonimbus, inside_cloud, horizon, two_layers, cirrus, "
         "above_clouds, cumulus_low_sun, cumulus_low_sun_behind; terrain: cumulus_noon, overcast, ridges_low_sun, "
         "snow_broken_cloud, dem_luxembourg; night: the term moon_disc, stars, sky_glow, moonlit_sky, twilight; "
         "weather: a preset, default fair-weather and thunderstorm)"},
        {"dem-dir", "DIR",
         "terrain only: the folder scripts/fetch_test_dems.sh fills (default build/test-data/dem), for dem_luxembourg"},
        {"repeats", "N", "timing repeats, median reported (default 3)"},
        {"reference-spp", "N",
         "Monte Carlo paths per pixel of every reference (default: per scenario; terrain: hemisphere directions, 64)"},
        {"threads", "N", "reference worker threads (default: all cores)"},
        {"sun-altitude", "DEG",
         "night, twilight rows: a sun altitude (-19 to +30 deg; repeat for more; default -6, -9 and -12)", true},
        {"table-orders", "N",
         "night, twilight rows: compare Bruneton's 4D tables of N orders (1 to 64; repeat for more; default 4)", true},
        {"octaves", "N", "with --calibrate: the octave count to fit a, b, c for (default 3)"},
        {"light-steps", "N", "with --calibrate: the light-march samples to fit for (default: the default preset's)"},
        {"evaluate-defaults", "",
         "with --calibrate: no fit, the shipped per-type defaults' errors on the calibration scenes"},
        {"reflection", "", "with --calibrate: also fit the reflected light's r and a_r (cloudReflectedSource)"},
        {"reflection-only", "", "with --calibrate: fit r and a_r alone, the octaves' constants at the shipped fit"},
        {"low-sun", "",
         "with --calibrate: fit the octaves' low-sun scale's mu_0 alone (a sweep, then golden sections), the rest at "
         "the shipped fit"},
        {"group", "G",
         "with --calibrate: only this group (cumulus, stratocumulus, stratus, cumulonimbus, cirrus, all)"},
        {"phase", "P",
         "with --calibrate: the phase model to fit for, dual_henyey_greenstein (default) or approximate_mie"},
        {"images", "",
         "clouds only: the reference's and the default's images, a heat map and per-pixel CSV in DIR/images (with "
         "--calibrate: each scene's per-pixel CSV at the fit)"},
        {"timing-only", "", "clouds only: the frame timing alone (DIR/clouds_timing.*), no references or error rows"},
        {"error-setting", "TEXT",
         "clouds, not with --timing-only: only the error rows whose \"knob value\" contains TEXT (alternatives "
         "separated by |) and the default row; no timing sweep"},
        {"timing-setting", "TEXT",
         "clouds, with --timing-only: only the timing settings whose name contains TEXT (alternatives separated by |), "
         "and the defaults' still and 1/16 sequence"},
        {"timing-size", "WxH",
         "clouds, terrain and night: the frame timing's image size (default 640x360, --quick 320x180 / terrain "
         "and night 160x90), e.g. "
         "1920x1080 on a GPU"},
        {"calibrate", "",
         "clouds only: fit the octave parameters a, b, c to the path tracer on separate calibration "
         "scenes (clouds_calibration.csv/.md; docs/clouds/README.md)"},
        deviceOption(),
    },
    1,
    1,
    runBench,
}};

}  // namespace
}  // namespace firmament::cli
