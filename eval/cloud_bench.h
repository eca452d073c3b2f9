#pragma once
// `firmament bench clouds`: the cloud march's error against run time (docs/clouds.md, "Benchmark").
// Per scenario the CPU cloud path tracer (clouds/reference_clouds.h) renders the clouds' light over
// the same medium (same noise texels, same weather map); the fast path sweeps one knob at a time
// (view steps, light steps, octaves) around the defaults, plus the first milestone's fixed-step
// baseline (64 uniform view steps, 6 light steps). Two diagnostic rows per scenario: the first
// milestone's light march (a fixed length of one layer thickness), and single scattering (one octave)
// against the path tracer limited to one scattering event. Sunlight only on both sides (no ambient, no aerial
// perspective), so the comparison isolates the march and its lighting approximation; the
// aerial_perspective rows turn the air on and compare with the fast path's own 256-step air march.
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace firmament {

struct CloudBenchConfig {
  std::filesystem::path outDir;
  bool quick = false;
  int repeats = 3;  // frame timing: median of this many after a warm-up
  // false: each still is rendered once, without the warm-up, and timed as that cold render (with any
  // pipeline compilation it needed). Its image, errors and samples are the same. For the tests, which
  // check the rows, not the times.
  bool timeFrames = true;
  int threads = 0;          // path tracer threads (0: all cores)
  int samplesPerPixel = 0;  // paths per reference pixel (0: 64, quick 16); more makes `corrected` robust
  std::string scenario;     // only this scenario (empty: all; checkCloudBenchConfig)
  // DIR/images/<scenario>_{reference,default}.exr (rgb: the clouds' light in cd/m^2, a: transmittance),
  // <scenario>_default_error.png (relative luminance error heat map, 0..20 %) and <scenario>_pixels.csv
  // (per pixel: the reference's luminance, standard error and transmittance, its even and odd paths' luminance, then
  // the luminance of every row, a column named knob=value each; where single_scattering rows run, the path tracer's
  // first order as `reference_order_1_luminance` before them, so a pixel's error splits into orders 1 and >= 2).
  bool images = false;
  // Only the frame timing (runCloudTiming, clouds_timing.*): no path-traced references, no error rows.
  // Not with images or a reference sample count (checkCloudBenchConfig).
  bool timingOnly = false;
  // The frame timing's image size (runCloudTiming); 0: 640x360 (quick 320x180), the size. A lent
  // GPU's 1920x1080 timings: --timing-only --timing-size 1920x1080.
  int timingWidth = 0, timingHeight = 0;
  // Only the frame-timing settings whose name contains this text (or one of several separated by '|'),
  // besides the defaults' still (every row's "vs default" needs it) and 1/16 sequence; empty: all. For
  // timing one knob against the defaults in minutes.
  std::string timingSetting;
  // Only the error rows whose "knob value" contains this text (or one of several separated by '|'),
  // besides the default row; empty: all. The first-order and fine-air references are rendered only if a
  // chosen row needs them, and the CLI then skips the timing sweep: the defaults against a quiet
  // reference (--error-setting default --reference-spp 1024) cost only the reference.
  std::string errorSetting;
  std::string environmentNote;
};

// InputError unless config.scenario is empty or names a scenario of this run (cumulus_noon,
// stratocumulus_sunset; without --quick also overcast, cumulonimbus, inside_cloud, horizon, two_layers,
// cirrus), and for timingOnly with images or samplesPerPixel (those are the error rows'). Run by
// runCloudBench and runCloudTiming; the CLI calls it first, to refuse bad input before any work.
void checkCloudBenchConfig(const CloudBenchConfig& config);

struct CloudBenchRow {
  std::string knob, value, scenario;
  double precomputeMs = 0.0;                            // the noise bake of the scenario's first render (once per seed)
  double frameMs = 0.0;                                 // median GPU time of clouds/render_clouds
  double relRmse = 0.0, psnrDb = 0.0, maxRelErr = 0.0;  // luminance of the clouds' light vs the path tracer
  double samplesPerPixel = 0.0;     // density evaluations per pixel (view + light march + the per-frame maps' bakes)
  double mapSamplesPerPixel = 0.0;  // the per-frame maps' bakes' part of samplesPerPixel (a fixed cost per frame)
  // Over the cloud pixels (reference transmittance < 0.95; clouds/reference_clouds.h
  // compareWithCloudReference): the error with the reference's Monte Carlo noise subtracted, the noise
  // alone (the rel RMSE of a perfect fast path), and mean(fast) / mean(reference) - 1.
  double relRmseNoiseCorrected = 0.0, referenceNoise = 0.0, meanBias = 0.0;
  // The mean bias over the darkest and the brightest quarter of the cloud pixels by the fast path's
  // own luminance (CloudReferenceError): dark > 0 > bright is a compressed range. 0 for the air rows.
  double darkQuartileBias = 0.0, brightQuartileBias = 0.0;
  // What the row is compared with: "path_tracer", "path_tracer_order_1" (single_scattering rows) or
  // "air_march_256" (aerial_perspective rows: the whole frame over the cloud pixels against the fast
  // path with the air marched per pixel in 256 steps; no reference noise).
  std::string against;
  std::string device;
};

std::vector<CloudBenchRow> runCloudBench(gpu::Context& context, CloudBenchConfig& config);
// clouds_results.csv (knob,value,scenario,precompute_ms,frame_ms,rel_rmse,psnr_db,max_rel_err,
// samples_per_pixel,rel_rmse_noise_corrected,ref_noise_rel_rmse,mean_bias,bias_dark_quarter,bias_bright_quarter,against,device)
// and clouds_report.md in config.outDir (prefixed: `bench all` writes the atmosphere's results.csv into the same
// folder).
void writeCloudBenchOutputs(const CloudBenchConfig& config, const std::vector<CloudBenchRow>& rows);

// The frame-time table: each scenario's view at 640x360 (320x180 with --quick), full default
// quality (ambient and aerial perspective on), for the shipped defaults, the fixed-step baseline (64
// uniform view steps, 6 light steps) and the reduced resolutions, in one run: median GPU ms of the cloud
// passes and density samples per image pixel. No reference (the errors are in clouds_results.csv).
struct CloudTimingRow {
  std::string scenario, setting;
  int width = 0, height = 0;
  double cloudMs = 0.0;  // the clouds' per-frame passes: the march, its upsampling or temporal resolve, the
                         // aerial-perspective volume, the per-frame maps' bakes (cloudPassMs)
  double frameMs = 0.0;  // every per-frame pass (sky included)
  double samplesPerPixel = 0.0;
  double mapSamplesPerPixel = 0.0;  // the per-frame maps' bakes' share of samplesPerPixel (not in the CSV)
  // Luminance of the whole frame against the defaults' frame at the same size, over the defaults' cloud
  // pixels (T < 0.95): relative RMSE and mean(setting) / mean(default) - 1 (0 for the defaults). What a
  // setting changes at a realistic size, beside its error against the path tracer at the bench's small one.
  double relRmseVsDefault = 0.0, biasVsDefault = 0.0;
  std::string device;
};
std::vector<CloudTimingRow> runCloudTiming(gpu::Context& context, const CloudBenchConfig& config);
// clouds_timing.csv (scenario,setting,width,height,cloud_ms,frame_ms,samples_per_pixel,rel_rmse_vs_default,
// bias_vs_default,device) and
// clouds_timing.md in config.outDir.
void writeCloudTimingOutputs(const CloudBenchConfig& config, const std::vector<CloudTimingRow>& rows);

}  // namespace firmament
