#pragma once
// `firmament bench clouds --calibrate --out DIR`: fits the octave multiple-scattering parameters a, b, c
// (Wrenninge et al. 2013; common/cloud_lighting.glsl) of the cloud march to the CPU path tracer, on
// calibration scenes kept separate from the benchmark's scenarios (other seeds, coverages, layer
// heights and sun angles), so the benchmark reports the fitted defaults on scenes the fit never saw.
// Sunlight only on both sides (no ambient, no aerial perspective), extinction x 0.3 as the benchmark
// (two thin scenes x 0.15, the cumulonimbus towers x 0.1; cirrus at its own extinction).
//
// The fit: per group of scenes (checkCloudCalibrationConfig lists them), Nelder-Mead (Nelder and Mead 1965) over
// x = (b, a / b, c, d / 2) in [0, 1]^4 (so a <= b holds by construction), started at the group's shipped
// constants, minimising the mean over the group's scenes of the squared relative RMSE of the clouds'
// luminance (cloud pixels; the reference's own noise adds the same constant to every candidate, so it
// does not move the minimum).
// docs/clouds.md, "Calibration", lists the scenes and the result.
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace firmament {

struct CloudCalibrationConfig {
  std::filesystem::path outDir;
  bool quick = false;       // smaller images (32x18 instead of 48x27), 64 paths per pixel
  int threads = 0;          // path tracer threads (0: all cores)
  int samplesPerPixel = 0;  // 0: 128 (quick 64): the fit needs a quiet reference
  int octaves = 3;          // the octave count the parameters are fitted for (the default)
  int lightSteps = 0;       // light-march samples (0: the default preset's, CloudMarchSettings::lightSteps)
  // No fit: each group's scenes rendered with the group's shipped constants (cloudTypeMultipleScattering
  // of its type; "all": the joint fit, cloudJointMultipleScattering), reported as the fit, to compare with a refit.
  bool evaluateDefaults = false;
  bool images = false;      // DIR/images/SCENE_pixels.csv: each scene's pixels with the fit's (or shipped) constants
  std::string group;        // only this group (its scenes' references alone); empty: every group
  int maxEvaluations = 90;  // objective evaluations per group (each renders the group's scenes)
  // Also fit the reflected light's weight r and depth scale a_r (cloudReflectedSource): x gains
  // (r / 4, a_r), started at the shipped reflection fit or, where it has none (r = 0), at (0.25, 0.5).
  // Without it the octaves alone are fitted, from their own shipped fit, with r = 0
  // (cloudTypeMultipleScattering's reflectedLight false).
  bool reflection = false;
  // Fit r and a_r alone, the octaves' a, b, c, d fixed at the group's shipped fit with the reflected light
  // (not the octaves-alone fit's).
  bool reflectionOnly = false;
  // Fit the octaves' low-sun scale's mu_0 alone (cloudOctaveLowSunScale), every other constant at the
  // group's shipped fit with the reflected light: a sweep over mu_0 in 0, 0.05, ..., 0.8 (each point's
  // per-scene errors in clouds_calibration_low_sun.csv), the best point refined by golden sections.
  bool lowSunOnly = false;
  // /clouds/lighting/phase on both sides: the octaves' c scales the phase's lobes, so each phase model
  // needs its own a, b, c ("dual_henyey_greenstein" or "approximate_mie").
  std::string phase = "dual_henyey_greenstein";
  std::string environmentNote;
};

struct CloudCalibrationSceneError {
  std::string scene;
  double relRmse = 0.0, noiseCorrected = 0.0, noiseFloor = 0.0, meanBias = 0.0;
};

struct CloudCalibrationFit {
  std::string group;  // "cumulus", "stratocumulus", "stratus", "cumulonimbus", "cirrus", "all" (the cumulus and
                      // stratocumulus scenes)
  double a = 0.5, b = 0.5, c = 0.5, d = 1.0;  // d: the diffusion floor's weight
  double r = 0.0, ra = 0.0;                   // the reflected light's weight and depth scale
  double lowSunMu = 0.0;                      // the octaves' low-sun scale's mu_0 (0: off)
  int evaluations = 0;
  double objectiveStart = 0.0, objectiveFit = 0.0;     // mean squared rel RMSE at a = b = c = 0.5, d = 1 and at the fit
  std::vector<CloudCalibrationSceneError> start, fit;  // per scene
};

// One point of the low-sun sweep (CloudCalibrationConfig::lowSunOnly).
struct CloudCalibrationSweepPoint {
  std::string group;
  double lowSunMu = 0.0, objective = 0.0;  // mean squared rel RMSE over the group
  std::vector<CloudCalibrationSceneError> scenes;
};

struct CloudCalibrationResult {
  std::vector<CloudCalibrationFit> fits;
  std::vector<CloudCalibrationSweepPoint> lowSunSweep;
  std::string device;
  double referenceSeconds = 0.0, fitSeconds = 0.0;
};

// InputError for a group that is not one of cumulus, stratocumulus, stratus, cumulonimbus, cirrus (each
// its own scenes) and all (the cumulus and stratocumulus scenes together: the joint fit), or for an
// unknown phase. Run by runCloudCalibration; the CLI calls it first, to refuse bad input before any work.
void checkCloudCalibrationConfig(const CloudCalibrationConfig& config);

CloudCalibrationResult runCloudCalibration(gpu::Context& context, const CloudCalibrationConfig& config);
// clouds_calibration.csv (group,a,b,c,d,scene,rel_rmse,rel_rmse_noise_corrected,ref_noise_rel_rmse,mean_bias,
// at) and clouds_calibration.md in config.outDir.
void writeCloudCalibrationOutputs(const CloudCalibrationConfig& config, const CloudCalibrationResult& result);

}  // namespace firmament
