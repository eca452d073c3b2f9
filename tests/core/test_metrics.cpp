// Image metrics on analytic cases, masks, non-finite pixels, the heat map and the compare JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_metrics.h"
#include "core/png_io.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

// A smooth HDR-like gradient, different per channel.
Image gradient(int width, int height, int channels = 3) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* p = image.at(x, y);
      p[0] = 1.0f + float(x);
      p[1] = 2.0f + float(y) * 3.0f;
      p[2] = 0.5f + float(x * y);
      if (channels == 4) p[3] = 1.0f;
    }
  return image;
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

TEST(Metrics, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  const Image a = gradient(16, 9);
  const ImageMetrics m = compareImages(a, a);
  EXPECT_EQ(m.comparedPixels, a.pixelCount());
  EXPECT_EQ(m.luminance.rmse, 0.0);
  EXPECT_EQ(m.luminance.relativeRmse, 0.0);
  EXPECT_EQ(m.luminance.maxAbsError, 0.0);
  EXPECT_EQ(m.luminance.meanBias, 0.0);
  for (const auto& c : m.rgb) EXPECT_EQ(c.rmse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnrDb) && m.psnrDb > 0);
  EXPECT_EQ(m.meanRelativeLuminanceError, 0.0);
  EXPECT_EQ(m.nonFiniteTest, 0u);
  const auto json = nlohmann::json::parse(metricsToJson(m));
  EXPECT_TRUE(json["psnr_db"].is_null());
  EXPECT_TRUE(json["identical"].get<bool>());
}

TEST(Metrics, ConstantOffsetGivesExactBiasAndRmse) {
  const Image reference = gradient(8, 5);
  Image test = reference;
  const float offset = 0.25f;  // exact in binary, and so is every sum below
  for (float& v : test.pixels) v += offset;
  const ImageMetrics m = compareImages(test, reference);

  double sumY = 0, sumY2 = 0, peak = 0;
  for (size_t i = 0; i < reference.pixelCount(); ++i) {
    const double y = luminance(reference.pixels.data() + 3 * i);
    sumY += y, sumY2 += y * y, peak = std::max(peak, y);
  }
  const double n = double(reference.pixelCount());
  // Y is linear, and the weights sum to 1, so Y is offset by exactly the same amount.
  EXPECT_NEAR(m.luminance.meanBias, offset, 1e-6);
  EXPECT_NEAR(m.luminance.rmse, offset, 1e-6);
  EXPECT_NEAR(m.luminance.maxAbsError, offset, 1e-6);
  EXPECT_NEAR(m.luminance.relativeMeanBias, offset / (sumY / n), 1e-6);
  EXPECT_NEAR(m.luminance.relativeRmse, offset / std::sqrt(sumY2 / n), 1e-6);
  EXPECT_NEAR(m.peakLuminance, peak, 1e-9);
  EXPECT_NEAR(m.psnrDb, 10.0 * std::log10(peak * peak / (offset * offset)), 1e-4);
  for (const auto& c : m.rgb) {
    EXPECT_DOUBLE_EQ(c.meanBias, offset);
    EXPECT_DOUBLE_EQ(c.rmse, offset);
    EXPECT_DOUBLE_EQ(c.maxAbsError, offset);
  }
}

TEST(Metrics, MaskExcludesPixels) {
  const Image reference = gradient(6, 4);
  Image test = reference;
  std::vector<uint8_t> mask(reference.pixelCount(), 1);
  // Pixel (2, 1) is wildly wrong and NaN at (3, 3): both masked out.
  test.at(2, 1)[0] = 1e6f;
  test.at(3, 3)[1] = std::numeric_limits<float>::quiet_NaN();
  mask[1 * 6 + 2] = 0;
  mask[3 * 6 + 3] = 0;
  const ImageMetrics masked = compareImages(test, reference, weightsFromMask(mask));
  EXPECT_EQ(masked.comparedPixels, reference.pixelCount() - 2);
  EXPECT_EQ(masked.luminance.rmse, 0.0);
  EXPECT_EQ(masked.rgb[0].maxAbsError, 0.0);
  EXPECT_EQ(masked.nonFiniteTest, 0u);

  const ImageMetrics all = compareImages(test, reference);
  EXPECT_GT(all.rgb[0].maxAbsError, 1e5);
  EXPECT_EQ(all.nonFiniteTest, 1u);
  EXPECT_EQ(all.comparedPixels, reference.pixelCount() - 1);
}

TEST(Metrics, WeightsWeighTheMean) {
  Image reference(2, 1, 3), test(2, 1, 3);
  std::fill(reference.pixels.begin(), reference.pixels.end(), 1.0f);
  test.pixels = {2, 2, 2, 1, 1, 1};  // error 1 at pixel 0, none at pixel 1
  const ImageMetrics m = compareImages(test, reference, {3.0f, 1.0f});
  EXPECT_DOUBLE_EQ(m.rgb[1].meanBias, 0.75);
  EXPECT_DOUBLE_EQ(m.rgb[1].rmse, std::sqrt(0.75));
  EXPECT_DOUBLE_EQ(m.weightSum, 4.0);
}

TEST(Metrics, NonFinitePixelsAreCountedNotAveraged) {
  const Image reference = gradient(4, 4);
  Image test = reference;
  test.at(0, 0)[2] = std::numeric_limits<float>::infinity();
  Image badReference = reference;
  badReference.at(1, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  const ImageMetrics m = compareImages(test, badReference);
  EXPECT_EQ(m.nonFiniteTest, 1u);
  EXPECT_EQ(m.nonFiniteReference, 1u);
  EXPECT_EQ(m.comparedPixels, 14u);
  EXPECT_EQ(m.luminance.rmse, 0.0);
  EXPECT_TRUE(std::isfinite(m.luminance.meanReference));
}

TEST(Metrics, SizeMismatchAndBadMaskAreInputErrors) {
  EXPECT_THROW(compareImages(gradient(4, 4), gradient(4, 5)), InputError);
  EXPECT_THROW(compareImages(gradient(4, 4), gradient(4, 4), std::vector<float>(3, 1.0f)), InputError);
  EXPECT_THROW(compareImages(gradient(1, 1), gradient(1, 1), {-1.0f}), InputError);
  EXPECT_NO_THROW(compareImages(gradient(4, 4, 4), gradient(4, 4, 3)));  // alpha is not compared
}

TEST(Metrics, RelativeErrorUsesFloorForDarkPixels) {
  Image reference(2, 1, 3), test(2, 1, 3);
  reference.pixels = {100, 100, 100, 0, 0, 0};
  test.pixels = {110, 110, 110, 0.5f, 0.5f, 0.5f};
  const double floor = relativeErrorFloor(reference);
  EXPECT_NEAR(floor, 0.01 * 50.0, 1e-12);  // 1 % of the mean luminance
  const std::vector<float> e = relativeLuminanceError(test, reference);
  EXPECT_NEAR(e[0], 0.1, 1e-6);
  EXPECT_NEAR(e[1], 0.5 / floor, 1e-6);
  const ImageMetrics m = compareImages(test, reference);
  EXPECT_NEAR(m.meanRelativeLuminanceError, (0.1 + 1.0) / 2, 1e-6);
}

TEST(Heatmap, ColourMapEndsAndScale) {
  EXPECT_EQ(heatmapColor(0.0), (std::array<uint8_t, 3>{0x44, 0x01, 0x54}));
  EXPECT_EQ(heatmapColor(1.0), (std::array<uint8_t, 3>{0xfd, 0xe7, 0x25}));
  EXPECT_EQ(heatmapColor(7.0), heatmapColor(1.0));
  EXPECT_EQ(heatmapColor(-1.0), heatmapColor(0.0));
  // Perceptually ordered: brightness (sum) increases along the map.
  int previous = -1;
  for (double t = 0; t <= 1.0; t += 0.01) {
    const auto c = heatmapColor(t);
    const int sum = c[0] + c[1] + c[2];
    EXPECT_GE(sum, previous - 2) << t;
    previous = sum;
  }
}

TEST(Heatmap, PixelsMapThroughScaleAndMaskAndNanAreMarked) {
  Image reference(4, 1, 3), test(4, 1, 3);
  std::fill(reference.pixels.begin(), reference.pixels.end(), 10.0f);
  test.pixels = {10, 10, 10, 10.5f, 10.5f, 10.5f, 20, 20, 20, std::nanf(""), 10, 10};
  const std::vector<float> weights = {1, 1, 1, 1};
  const auto rgb = errorHeatmapRgb8(test, reference, 0.1, weights);
  auto at = [&](int x) { return std::array<uint8_t, 3>{rgb[3 * x], rgb[3 * x + 1], rgb[3 * x + 2]}; };
  EXPECT_EQ(at(0), heatmapColor(0.0));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(at(1)[c], heatmapColor(0.5)[c], 1);  // 5 % of a 10 % scale (float)
  EXPECT_EQ(at(2), heatmapColor(1.0));                                         // 100 % error, clipped at the top
  EXPECT_EQ(at(3), (std::array<uint8_t, 3>{255, 0, 255}));
  const auto masked = errorHeatmapRgb8(test, reference, 0.1, {1, 0, 1, 1});
  EXPECT_EQ(masked[3], 64);
  EXPECT_THROW(errorHeatmapRgb8(test, reference, 0.0), InputError);

  const auto path = test::scratchDir("heatmap") / "heat.png";
  writeErrorHeatmapPng(path, test, reference, 0.1);
  const Image8 png = readPng(path);
  EXPECT_EQ(png.width, 4);
  EXPECT_EQ(png.channels, 3);
  EXPECT_EQ(png.pixels, rgb);
  EXPECT_EQ(png.text.at("firmament.heatmap_scale"), "0.1");
}

}  // namespace
}  // namespace firmament
