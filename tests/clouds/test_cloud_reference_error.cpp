// compareWithCloudReference's range diagnostic (clouds/reference_clouds.h): the mean bias over the
// darkest and brightest quarter of the cloud pixels, split by the fast path's own luminance. Synthetic
// images with known answers; no GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "clouds/reference_clouds.h"

namespace firmament {
namespace {

// A w x 1 reference whose pixels are all cloud (transmittance 0.5), luminance `truth` plus Gaussian
// noise of standard error `se` per pixel (reported as the pixel's standard error).
CloudReferenceImage referenceOf(const std::vector<double>& truth, double se, uint32_t seed) {
  CloudReferenceImage ref;
  ref.image = Image(int(truth.size()), 1, 4);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (size_t i = 0; i < truth.size(); ++i) {
    const double y = truth[i] + se * noise(rng);
    ref.luminance.push_back(y);
    ref.luminanceStandardError.push_back(se);
    for (int c = 0; c < 3; ++c) ref.image.pixels[4 * i + c] = float(y);
    ref.image.pixels[4 * i + 3] = 0.5f;
  }
  return ref;
}

// A grey fast-path image of the given luminances (r = g = b, so the Rec.709 luminance is the value).
Image imageOf(const std::vector<double>& luminance) {
  Image image(int(luminance.size()), 1, 4);
  for (size_t i = 0; i < luminance.size(); ++i) {
    for (int c = 0; c < 3; ++c) image.pixels[4 * i + c] = float(luminance[i]);
    image.pixels[4 * i + 3] = 0.5f;
  }
  return image;
}

// Luminances 1..400 in a shuffled order (the quarters must not depend on the pixels' order).
std::vector<double> ramp() {
  std::vector<double> y;
  for (int i = 1; i <= 400; ++i) y.push_back(double(i));
  std::shuffle(y.begin(), y.end(), std::mt19937(7));
  return y;
}

TEST(CloudReferenceError, AModelThatCompressesTheRangeShowsInTheQuarters) {
  const std::vector<double> truth = ramp();
  const CloudReferenceImage ref = referenceOf(truth, 0.0, 1);
  // a = sqrt(200 y): equal to y at y = 200, brighter below, darker above.
  std::vector<double> compressed;
  for (double y : truth) compressed.push_back(std::sqrt(200.0 * y));
  const CloudReferenceError e = compareWithCloudReference(imageOf(compressed), ref);
  // The quarters are y = 1..100 and 301..400: sum sqrt(200 y) / sum y - 1 over each.
  double darkA = 0.0, darkY = 0.0, brightA = 0.0, brightY = 0.0;
  for (int y = 1; y <= 100; ++y) darkA += std::sqrt(200.0 * y), darkY += y;
  for (int y = 301; y <= 400; ++y) brightA += std::sqrt(200.0 * y), brightY += y;
  EXPECT_NEAR(e.darkQuartileBias, darkA / darkY - 1.0, 1e-6);
  EXPECT_NEAR(e.brightQuartileBias, brightA / brightY - 1.0, 1e-6);
  EXPECT_GT(e.darkQuartileBias, 0.5);
  EXPECT_LT(e.brightQuartileBias, -0.1);

  // A uniform scale is the same bias everywhere: no range error.
  std::vector<double> scaled;
  for (double y : truth) scaled.push_back(0.9 * y);
  const CloudReferenceError s = compareWithCloudReference(imageOf(scaled), ref);
  EXPECT_NEAR(s.darkQuartileBias, -0.1, 1e-6);
  EXPECT_NEAR(s.brightQuartileBias, -0.1, 1e-6);
  EXPECT_NEAR(s.meanBias, -0.1, 1e-6);
}

TEST(CloudReferenceError, TheReferencesNoiseDoesNotFakeACompressedRange) {
  // A perfect fast path (a = the truth) against a noisy reference: luminances 0.5..200, noise of
  // standard error 10 per pixel, 4000 pixels. Split by a, each quarter's mean reference is unbiased:
  // its bias is 0 within its standard error (10 / sqrt(1000) over a mean of ~25 in the dark quarter,
  // 1.3 %), so the bound of 4 % is 3 standard errors. Split by the noisy reference, the dark quarter
  // collects the pixels whose noise came out low and shows the perfect model too bright by more than
  // that (checked last).
  std::vector<double> truth;
  for (int k = 0; k < 10; ++k)
    for (double y : ramp()) truth.push_back(0.5 * y);
  const CloudReferenceImage ref = referenceOf(truth, 10.0, 3);
  const CloudReferenceError e = compareWithCloudReference(imageOf(truth), ref);
  EXPECT_LT(std::abs(e.darkQuartileBias), 0.04) << e.darkQuartileBias;
  EXPECT_LT(std::abs(e.brightQuartileBias), 0.04) << e.brightQuartileBias;

  // The split by the reference, for the record of what the bound guards against.
  std::vector<std::pair<double, double>> byReference;
  for (size_t i = 0; i < truth.size(); ++i) byReference.push_back({ref.luminance[i], truth[i]});
  std::sort(byReference.begin(), byReference.end());
  double a = 0.0, y = 0.0;
  for (size_t i = 0; i < byReference.size() / 4; ++i) a += byReference[i].second, y += byReference[i].first;
  EXPECT_GT(a / y - 1.0, 0.04) << "a split by the noisy reference shows the dark quarter too bright";
}

}  // namespace
}  // namespace firmament
