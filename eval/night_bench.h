#pragma once
// `firmament bench night` (docs/night.md, "Error and cost: bench night"): each night term of the frame
// against a CPU reference that shares none of the frame's approximations, and the term's pass time:
//  - the Moon's disc (night and daytime): its pixels' sum against the Moon's illuminance (K&S 1991) times the
//    clear-sky reference's spectral transmittance;
//  - the stars: their pixels' sum over a fisheye against the catalogue's illuminances times the reference's
//    transmittance, and the brightest star alone;
//  - the sky's own light (airglow, zodiacal light, faint stars) at the zenith and 80 deg from it against the
//    van Rhijn law through the air: the spectral light above the air times the reference's transmittance,
//    plus the isotropic-field estimate of what the air scatters of it;
//  - the moonlit sky against the CPU reference (atmosphere/reference_renderer.h: single scattering by
//    quadrature, multiple by path tracing) lit from the Moon's direction with its spectrum;
//  - the twilight's ground illuminance at sun -6, -9, -12 deg (or the altitudes asked for), the frame and its
//    other models (f_ms, Bruneton's 4D tables of each order asked for) against the same reference integrated
//    over the sky.
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace firmament {

struct NightBenchConfig {
  std::filesystem::path outDir;
  bool quick = false;
  int repeats = 3;
  int threads = 0;       // reference worker threads (0: all cores)
  int referenceSpp = 0;  // reference paths per direction for orders >= 2 (0: 128, --quick 32)
  int timingWidth = 640, timingHeight = 360;
  std::string term;  // only this term (empty: all): one of kNightBenchTerms
  // The twilight rows' sun altitudes (deg, -30 to +30) and the orders of the 4D tables compared there.
  std::vector<double> twilightAltitudesDeg = {-6.0, -9.0, -12.0};
  std::vector<int> twilightTableOrders = {4};
  std::string environmentNote;
};
inline constexpr const char* kNightBenchTerms[] = {"moon_disc", "stars", "sky_glow", "moonlit_sky", "twilight"};
// InputError for a term that does not exist (before any work).
void checkNightBenchConfig(const NightBenchConfig& config);

struct NightBenchRow {
  std::string term, quantity, unit;
  double frame = 0.0, reference = 0.0;
  double relError = 0.0;  // frame / reference - 1 (moonlit sky: relative RMSE over the pixels)
  double meanBias = 0.0;  // moonlit sky: mean frame / mean reference - 1; else relError
  std::string passes;     // the GPU passes timed
  double passMs = 0.0;    // their GPU time at the timing size (median over repeats)
  double referenceSeconds = 0.0;
  std::string note;
};

std::vector<NightBenchRow> runNightBench(gpu::Context& context, const NightBenchConfig& config);
// DIR/night_results.csv and DIR/night_report.md.
void writeNightBenchOutputs(const NightBenchConfig& config, const std::vector<NightBenchRow>& rows,
                            const std::string& device);

}  // namespace firmament
