#pragma once
// Error metrics between a test image and a reference, and a relative-error heat map
// (definitions in docs/formats.md, "Metrics"). Sums run in double over the pixels with weight > 0
// whose R, G, B are finite in both images; weights are a mask (0/1) or any non-negative per-pixel
// weights, empty = every pixel weighs 1. Luminance is Y = 0.2126 R + 0.7152 G + 0.0722 B (core/color.h).
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace firmament {

// For one quantity (luminance or a channel); a = test, b = reference, mean = weighted mean.
struct ErrorStats {
  double rmse = 0.0;              // sqrt(mean((a − b)²))
  double relativeRmse = 0.0;      // rmse / sqrt(mean(b²)); 0 when both are 0, +inf when only b² is 0
  double maxAbsError = 0.0;       // max |a − b|
  double meanBias = 0.0;          // mean(a − b)
  double relativeMeanBias = 0.0;  // mean(a − b) / mean(b); 0 when both are 0, ±inf when only mean(b) is 0
  double meanTest = 0.0;          // mean(a)
  double meanReference = 0.0;     // mean(b)
};

struct ImageMetrics {
  int width = 0;
  int height = 0;
  size_t comparedPixels = 0;      // weight > 0 and finite in both images
  double weightSum = 0.0;         // Σ weights over the compared pixels
  size_t nonFiniteTest = 0;       // pixels with weight > 0 and a NaN/Inf in R, G or B of the test
  size_t nonFiniteReference = 0;  // the same in the reference
  ErrorStats luminance;
  std::array<ErrorStats, 3> rgb;            // R, G, B
  double peakLuminance = 0.0;               // max reference luminance over the compared pixels (the PSNR peak)
  double psnrDb = 0.0;                      // 10·log10(peak² / mean((Ya − Yb)²)); +inf when the images agree
  double relativeErrorFloor = 0.0;          // ε of the per-pixel relative error (relativeErrorFloor())
  double meanRelativeLuminanceError = 0.0;  // mean(|Ya − Yb| / max(Yb, ε)) — what the heat map shows
};

// Nonzero → 1, zero → 0.
std::vector<float> weightsFromMask(const std::vector<uint8_t>& mask);

// Compares `test` with `reference`. Different sizes, a weight count other than the pixel count, or
// a negative or non-finite weight → InputError. The channel counts may differ (A is not compared).
// With no compared pixel every error is 0 and psnrDb is NaN.
ImageMetrics compareImages(const Image& test, const Image& reference, const std::vector<float>& weights = {});

// ε = 1 % of the weighted mean reference luminance over the finite pixels (at least 1e-12 cd/m²):
// pixels much darker than the scene's mean have their error measured against it instead of their
// own, near-zero value, so a dark pixel cannot dominate a relative error.
double relativeErrorFloor(const Image& reference, const std::vector<float>& weights = {});

// Per pixel |Ya − Yb| / max(Yb, ε), ε = relativeErrorFloor(reference, weights); NaN where a pixel
// is masked out or non-finite in either image. Same size checks as compareImages.
std::vector<float> relativeLuminanceError(const Image& test, const Image& reference,
                                          const std::vector<float>& weights = {});

// The heat map's perceptually ordered colour map (viridis, van der Walt & Smith 2015, CC0):
// t ∈ [0, 1] from dark purple through blue and green to yellow; t outside is clamped.
std::array<uint8_t, 3> heatmapColor(double t);

// RGB8 heat map: relative luminance error e mapped to heatmapColor(e / scale), so `scale` (> 0,
// e.g. 0.1 = 10 %) and above is yellow. Masked-out pixels are dark grey (64, 64, 64); pixels
// non-finite in either image are magenta (255, 0, 255). A scale that is not a positive finite
// number → InputError.
std::vector<uint8_t> errorHeatmapRgb8(const Image& test, const Image& reference, double scale,
                                      const std::vector<float>& weights = {});
// The same written as a PNG (atomically), with the scale in its tEXt entries.
void writeErrorHeatmapPng(const std::filesystem::path& path, const Image& test, const Image& reference, double scale,
                          const std::vector<float>& weights = {});

// The metrics as a JSON document (keys in docs/formats.md); infinities and NaN are written as null.
std::string metricsToJson(const ImageMetrics& metrics);

}  // namespace firmament
