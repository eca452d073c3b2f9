#pragma once
// `firmament bench atmosphere`: error against run time of the fast GPU sky (SkyRenderer) for each
// of its quality knobs, one knob at a time around the shipped defaults, on a few scenarios, against
// the CPU reference (docs/bench.md). The sweep is data: a list of scenarios (scene overrides) and a
// list of knobs (named values that edit SkyRenderOptions), so new knobs are one entry each.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "atmosphere/reference_renderer.h"
#include "core/image.h"
#include "gpu/context.h"
#include "sky/sky_renderer.h"

namespace firmament {

// A view of the clear sky to measure: a scene file eval/scenarios/atmosphere/<name>.json (eval/scenarios.h),
// the image size and the reference's sampling (more paths where its Monte Carlo noise is larger, e.g.
// twilight).
struct BenchScenario {
  std::string name;                    // e.g. "noon": eval/scenarios/atmosphere/noon.json
  std::string description;             // one line for the report
  std::vector<std::string> overrides;  // on the scene file, e.g. "/sun/zenith_deg=30" (size overrides are added)
  int width = 48, height = 27;
  int referenceSamples = 2048;  // Monte Carlo paths per pixel of the reference
};

// One value of a knob: its label in results.csv and what it changes.
struct BenchKnobValue {
  std::string value;
  std::function<void(SkyRenderOptions&)> apply;
};

struct BenchKnob {
  std::string name;          // results.csv "knob", e.g. "view_steps"
  std::string description;   // what it is, for the report
  std::string defaultValue;  // the shipped default's label
  std::vector<BenchKnobValue> values;
  bool tables = false;                   // it changes the precomputed tables (its cost is precompute_ms, else frame_ms)
  std::vector<std::string> quickValues;  // the values --quick keeps (empty: the first and the default)
};

// The shipped scenarios and knobs; `quick` shrinks the images, the reference's paths and the knob
// values (docs/bench.md says what it drops).
std::vector<BenchScenario> atmosphereBenchScenarios(bool quick);
std::vector<BenchKnob> atmosphereBenchKnobs(bool quick);

struct AtmosphereBenchConfig {
  std::filesystem::path outDir;  // results.csv, report.md, plots, references/ (the cache)
  std::vector<BenchScenario> scenarios;
  std::vector<BenchKnob> knobs;
  SkyRenderOptions defaults;  // the options every knob varies one field of
  int repeats = 3;            // timings: median of this many after a warm-up
  bool quick = false;
  bool fullFrameTiming = true;  // also time the defaults at 1280x720 (both methods)
  int fullFrameWidth = 1280, fullFrameHeight = 720;
  ReferenceQuality referenceQuality;  // samplesPerPixel is taken from each scenario
  std::string environmentNote;        // for the report, e.g. the machine's load average
};

// A precompute that takes longer than this is timed once instead of `repeats` times (the 4D
// scattering tables take ~20 s on lavapipe; their relative timing noise is small).
inline constexpr double kSinglePrecomputeMilliseconds = 2000.0;

// One row of results.csv.
struct BenchRow {
  std::string knob, value, scenario;
  double precomputeMs = 0.0;  // median GPU time of the tables, forced to recompute
  double frameMs = 0.0;       // median GPU time of the per-frame passes at the scenario's size
  double relRmse = 0.0;       // luminance: sqrt(mean((Ya − Yb)²)) / sqrt(mean(Yb²))
  double psnrDb = 0.0;        // luminance: 10 log10(max(Yb)² / mean((Ya − Yb)²))
  double maxRelErr = 0.0;     // max over pixels of |Ya − Yb| / max(Yb, ε), ε = 1 % of mean(Yb)
  std::string device;
};

// The reference of one scenario and its own Monte Carlo noise.
struct BenchReference {
  std::string scenario;
  int width = 0, height = 0, samplesPerPixel = 0, wavelengths = 0;
  double seconds = 0.0;  // when it was rendered (0 if unknown)
  bool fromCache = false;
  std::filesystem::path file;
  double medianRelativeNoise = 0.0, p95RelativeNoise = 0.0;  // SE(Y)/Y over the pixels
  // The errors that noise alone causes in expectation: relative RMSE sqrt(mean(SE²)/mean(Y²)) and
  // PSNR 10 log10(max(Y)² / mean(SE²)); a measured error near these is the reference's, not the
  // fast path's.
  double noiseRelRmse = 0.0, noisePsnrDb = 0.0;
  double meanSquaredNoise = 0.0;  // mean(SE²), cd²/m⁴
  double meanSquaredLuminance = 0.0, peakLuminance = 0.0;
};

struct FullFrameTiming {
  std::string method;  // "lut" or "per-pixel"
  int width = 0, height = 0;
  double frameMs = 0.0;                 // median
  std::vector<gpu::PassTiming> passes;  // of the median run
};

struct AtmosphereBenchResult {
  std::string device;
  std::vector<BenchRow> rows;
  std::vector<BenchReference> references;
  std::vector<FullFrameTiming> fullFrame;
  std::vector<gpu::PassTiming> defaultTablePasses;  // per pass of a default precompute (median run)
  std::string timingNote;                           // non-empty when the device has no timestamps (wall clock)
  double seconds = 0.0;                             // wall clock of the whole bench
};

// Renders (or reads from outDir/references) each scenario's reference, then for every knob value
// and scenario renders the fast path `repeats` times with freshly computed tables and `repeats`
// times per frame, and compares with the reference. Progress bars on stderr.
AtmosphereBenchResult runAtmosphereBench(gpu::Context& context, const AtmosphereBenchConfig& config);

// results.csv, report.md and one SVG plot per scenario (error vs run time) in config.outDir.
void writeAtmosphereBenchOutputs(const AtmosphereBenchConfig& config, const AtmosphereBenchResult& result);

// The scene of a scenario: its scene file with its overrides and size.
Scene benchScenarioScene(const BenchScenario& scenario);

// max over pixels of |Ya − Yb| / max(Yb, ε), ε = relativeErrorFloor(reference) (1 % of the mean
// reference luminance): the worst pixel's relative luminance error, dark pixels measured against ε.
double maxRelativeLuminanceError(const Image& test, const Image& reference);

}  // namespace firmament
