#pragma once
// `firmament bench terrain` (docs/terrain.md, "Error and cost per knob"): per scenario of
// eval/scenarios/terrain/ and per knob of the terrain's light (cloud shadow map size and extent, sky-light
// model, self-shadowing), the relative error of the ground's luminance at the surface against the CPU
// reference (eval/terrain_reference.h) and the terrain passes' GPU time (median over repeats) at the
// timing size.
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/context.h"

namespace firmament {

struct TerrainBenchConfig {
  std::filesystem::path outDir;
  bool quick = false;
  std::string scenario;  // only this one (empty: all, or the quick ones with --quick)
  int repeats = 3;
  int threads = 0;
  int skyDirections = 0;  // reference hemisphere directions per pixel (0: 64, --quick 16)
  // The reference's view rays per pixel, pixelSide² (TerrainReferenceSettings::pixelSide): the pixel's
  // area, which the terrain's level of detail filters to (3: 9 sub-pixels; 1: the pixel's centre).
  int referencePixelSide = 3;
  int timingWidth = 640, timingHeight = 360;
  std::filesystem::path demDir = "build/test-data/dem";  // scripts/fetch_test_dems.sh's folder
  std::string environmentNote;
};

struct TerrainBenchRow {
  std::string scenario, knob, value;
  int pixels = 0, shadowPixels = 0;
  double relRmse = 0.0, noiseFloor = 0.0, noiseCorrected = 0.0, meanBias = 0.0, shadowBias = 0.0, litBias = 0.0;
  double meanReference = 0.0, meanTest = 0.0;
  double terrainMs = 0.0, frameMs = 0.0;  // medians at the timing size
  double referenceSeconds = 0.0;
};

// InputError for a scenario that does not exist or a DEM scenario without its file (before any work).
void checkTerrainBenchConfig(const TerrainBenchConfig& config);
std::vector<TerrainBenchRow> runTerrainBench(gpu::Context& context, const TerrainBenchConfig& config);
// DIR/terrain_results.csv and DIR/terrain_report.md.
void writeTerrainBenchOutputs(const TerrainBenchConfig& config, const std::vector<TerrainBenchRow>& rows,
                              const std::string& device);

}  // namespace firmament
