#include "core/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "core/error.h"
#include "core/png_io.h"

namespace firmament {

namespace {

bool finiteRgb(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

void checkComparable(const Image& test, const Image& reference, const std::vector<float>& weights) {
  if (test.width != reference.width || test.height != reference.height)
    throw InputError("image sizes differ: " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                     " (test) vs " + std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     " (reference)");
  if (!weights.empty() && weights.size() != reference.pixelCount())
    throw InputError("mask has " + std::to_string(weights.size()) + " entries, the images have " +
                     std::to_string(reference.pixelCount()) + " pixels");
  for (float w : weights)
    if (!(w >= 0.0f) || !std::isfinite(w)) throw InputError("mask weights must be finite and non-negative");
}

float weightAt(const std::vector<float>& weights, size_t i) { return weights.empty() ? 1.0f : weights[i]; }

// Running weighted sums for one quantity.
struct Accumulator {
  double sumDiff = 0, sumDiff2 = 0, sumRef = 0, sumRef2 = 0, sumTest = 0, maxAbs = 0;
  void add(double w, double a, double b) {
    const double d = a - b;
    sumDiff += w * d;
    sumDiff2 += w * d * d;
    sumRef += w * b;
    sumRef2 += w * b * b;
    sumTest += w * a;
    maxAbs = std::max(maxAbs, std::abs(d));
  }
};

// x / y with 0/0 = 0 (nothing to be wrong about) and x/0 = ±inf.
double safeRatio(double x, double y) {
  if (y != 0.0) return x / y;
  if (x == 0.0) return 0.0;
  return x > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

ErrorStats finish(const Accumulator& acc, double weightSum) {
  ErrorStats s;
  if (weightSum <= 0.0) return s;
  const double meanDiff2 = acc.sumDiff2 / weightSum;
  s.rmse = std::sqrt(meanDiff2);
  s.relativeRmse = safeRatio(s.rmse, std::sqrt(acc.sumRef2 / weightSum));
  s.maxAbsError = acc.maxAbs;
  s.meanBias = acc.sumDiff / weightSum;
  s.meanReference = acc.sumRef / weightSum;
  s.meanTest = acc.sumTest / weightSum;
  s.relativeMeanBias = safeRatio(s.meanBias, s.meanReference);
  return s;
}

using Json = nlohmann::ordered_json;  // keys in the documented order, not sorted

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json toJson(const ErrorStats& s) {
  return {{"rmse", number(s.rmse)},
          {"relative_rmse", number(s.relativeRmse)},
          {"max_abs_error", number(s.maxAbsError)},
          {"mean_bias", number(s.meanBias)},
          {"relative_mean_bias", number(s.relativeMeanBias)},
          {"mean_test", number(s.meanTest)},
          {"mean_reference", number(s.meanReference)}};
}

}  // namespace

std::vector<float> weightsFromMask(const std::vector<uint8_t>& mask) {
  std::vector<float> weights(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) weights[i] = mask[i] ? 1.0f : 0.0f;
  return weights;
}

double relativeErrorFloor(const Image& reference, const std::vector<float>& weights) {
  double sum = 0.0, weightSum = 0.0;
  for (size_t i = 0; i < reference.pixelCount(); ++i) {
    const float* b = reference.pixels.data() + i * size_t(reference.channels);
    const double w = weightAt(weights, i);
    if (w <= 0.0 || !finiteRgb(b)) continue;
    sum += w * luminanceRec709(b);
    weightSum += w;
  }
  const double mean = weightSum > 0.0 ? sum / weightSum : 0.0;
  return std::max(0.01 * mean, 1e-12);
}

ImageMetrics compareImages(const Image& test, const Image& reference, const std::vector<float>& weights) {
  checkComparable(test, reference, weights);
  ImageMetrics m;
  m.width = reference.width;
  m.height = reference.height;
  m.relativeErrorFloor = relativeErrorFloor(reference, weights);
  Accumulator luminance, channel[3];
  double sumRelative = 0.0;
  for (size_t i = 0; i < reference.pixelCount(); ++i) {
    const double w = weightAt(weights, i);
    if (w <= 0.0) continue;
    const float* a = test.pixels.data() + i * size_t(test.channels);
    const float* b = reference.pixels.data() + i * size_t(reference.channels);
    const bool finiteA = finiteRgb(a), finiteB = finiteRgb(b);
    m.nonFiniteTest += !finiteA;
    m.nonFiniteReference += !finiteB;
    if (!finiteA || !finiteB) continue;
    const double ya = luminanceRec709(a), yb = luminanceRec709(b);
    luminance.add(w, ya, yb);
    for (int c = 0; c < 3; ++c) channel[c].add(w, a[c], b[c]);
    sumRelative += w * std::abs(ya - yb) / std::max(yb, m.relativeErrorFloor);
    m.peakLuminance = std::max(m.peakLuminance, yb);
    m.weightSum += w;
    ++m.comparedPixels;
  }
  m.luminance = finish(luminance, m.weightSum);
  for (int c = 0; c < 3; ++c) m.rgb[size_t(c)] = finish(channel[c], m.weightSum);
  if (m.comparedPixels == 0) {
    m.psnrDb = std::numeric_limits<double>::quiet_NaN();
  } else {
    const double mse = luminance.sumDiff2 / m.weightSum;
    m.psnrDb = mse > 0.0 ? 10.0 * std::log10(m.peakLuminance * m.peakLuminance / mse)
                         : std::numeric_limits<double>::infinity();
    m.meanRelativeLuminanceError = sumRelative / m.weightSum;
  }
  return m;
}

std::vector<float> relativeLuminanceError(const Image& test, const Image& reference,
                                          const std::vector<float>& weights) {
  checkComparable(test, reference, weights);
  const double floor = relativeErrorFloor(reference, weights);
  std::vector<float> error(reference.pixelCount(), std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < reference.pixelCount(); ++i) {
    const float* a = test.pixels.data() + i * size_t(test.channels);
    const float* b = reference.pixels.data() + i * size_t(reference.channels);
    if (weightAt(weights, i) <= 0.0f || !finiteRgb(a) || !finiteRgb(b)) continue;
    const double yb = luminanceRec709(b);
    error[i] = float(std::abs(luminanceRec709(a) - yb) / std::max(yb, floor));
  }
  return error;
}

std::array<uint8_t, 3> heatmapColor(double t) {
  // viridis sampled at t = k/9 (matplotlib's viridis, CC0); linear interpolation between samples.
  static constexpr uint8_t kViridis[10][3] = {
      {0x44, 0x01, 0x54}, {0x48, 0x28, 0x78}, {0x3e, 0x4a, 0x89}, {0x31, 0x68, 0x8e}, {0x26, 0x82, 0x8e},
      {0x1f, 0x9e, 0x89}, {0x35, 0xb7, 0x79}, {0x6d, 0xcd, 0x59}, {0xb4, 0xde, 0x2c}, {0xfd, 0xe7, 0x25}};
  if (!(t > 0.0)) t = 0.0;  // also NaN
  t = std::min(t, 1.0) * 9.0;
  const int k = std::min(int(t), 8);
  const double f = t - k;
  std::array<uint8_t, 3> rgb;
  for (int c = 0; c < 3; ++c)
    rgb[size_t(c)] = uint8_t(std::lround(kViridis[k][c] + f * (double(kViridis[k + 1][c]) - kViridis[k][c])));
  return rgb;
}

std::vector<uint8_t> errorHeatmapRgb8(const Image& test, const Image& reference, double scale,
                                      const std::vector<float>& weights) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw InputError("heat map scale must be a positive number, got " + std::to_string(scale));
  const std::vector<float> error = relativeLuminanceError(test, reference, weights);
  std::vector<uint8_t> rgb(error.size() * 3);
  for (size_t i = 0; i < error.size(); ++i) {
    uint8_t* q = rgb.data() + 3 * i;
    std::array<uint8_t, 3> color;
    if (!std::isnan(error[i])) {
      color = heatmapColor(error[i] / scale);
    } else if (weightAt(weights, i) <= 0.0f) {
      color = {64, 64, 64};
    } else {
      color = {255, 0, 255};
    }
    std::copy(color.begin(), color.end(), q);
  }
  return rgb;
}

void writeErrorHeatmapPng(const std::filesystem::path& path, const Image& test, const Image& reference, double scale,
                          const std::vector<float>& weights) {
  const std::vector<uint8_t> rgb = errorHeatmapRgb8(test, reference, scale, weights);
  char scaleText[64];
  std::snprintf(scaleText, sizeof(scaleText), "%.6g", scale);
  writePng(path, reference.width, reference.height, 3, rgb.data(),
           {{"Software", "firmament compare"},
            {"firmament.heatmap", "relative luminance error |Ya-Yb|/max(Yb,eps), viridis"},
            {"firmament.heatmap_scale", scaleText}});
}

std::string metricsToJson(const ImageMetrics& m) {
  Json j;
  j["width"] = m.width;
  j["height"] = m.height;
  j["compared_pixels"] = m.comparedPixels;
  j["weight_sum"] = number(m.weightSum);
  j["non_finite_test"] = m.nonFiniteTest;
  j["non_finite_reference"] = m.nonFiniteReference;
  j["luminance"] = toJson(m.luminance);
  j["r"] = toJson(m.rgb[0]);
  j["g"] = toJson(m.rgb[1]);
  j["b"] = toJson(m.rgb[2]);
  j["peak_luminance"] = number(m.peakLuminance);
  j["psnr_db"] = number(m.psnrDb);
  j["identical"] = m.comparedPixels > 0 && m.luminance.rmse == 0.0 && m.rgb[0].rmse == 0.0 && m.rgb[1].rmse == 0.0 &&
                   m.rgb[2].rmse == 0.0;
  j["relative_error_floor"] = number(m.relativeErrorFloor);
  j["mean_relative_luminance_error"] = number(m.meanRelativeLuminanceError);
  return j.dump(2) + "\n";
}

}  // namespace firmament
