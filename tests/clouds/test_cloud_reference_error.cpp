// compareWithCloudReference's range diagnostic (clouds/reference_clouds.h): the mean bias over the
// darkest and brightest quarter of the cloud pixels, split by the reference's even-numbered paths and
// measured against its odd-numbered ones. Synthetic images with known answers; no GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "clouds/reference_clouds.h"

namespace firmament {
namespace {

// A w x 1 reference whose pixels are all cloud (transmittance 0.5): each half of the paths sees the
// luminance `truth` plus its own Gaussian noise of standard error `halfSe`; the full estimate is their
// mean (standard error halfSe / sqrt 2).
CloudReferenceImage referenceOf(const std::vector<double>& truth, double halfSe, uint32_t seed) {
  CloudReferenceImage ref;
  ref.image = Image(int(truth.size()), 1, 4);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (size_t i = 0; i < truth.size(); ++i) {
    const double even = truth[i] + halfSe * noise(rng), odd = truth[i] + halfSe * noise(rng);
    const double y = 0.5 * (even + odd);
    ref.luminance.push_back(y);
    ref.luminanceStandardError.push_back(halfSe / std::sqrt(2.0));
    ref.luminanceEvenPaths.push_back(even);
    ref.luminanceOddPaths.push_back(odd);
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

// Luminances 0.5..200 (`copies` times each of 400 values) in a shuffled order: the quarters must not
// depend on the pixels' order.
std::vector<double> ramp(int copies) {
  std::vector<double> y;
  for (int k = 0; k < copies; ++k)
    for (int i = 1; i <= 400; ++i) y.push_back(0.5 * i);
  std::shuffle(y.begin(), y.end(), std::mt19937(7));
  return y;
}

// The bias over the quarter of pixels with the lowest `by`, measured as sum(test) / sum(reference) - 1:
// the splits the diagnostic does not use, to show what they would report.
double darkQuarterBiasSplitBy(const std::vector<double>& by, const std::vector<double>& test,
                              const std::vector<double>& reference) {
  std::vector<size_t> order(by.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t l, size_t r) { return by[l] < by[r]; });
  double a = 0.0, y = 0.0;
  for (size_t k = 0; k < order.size() / 4; ++k) a += test[order[k]], y += reference[order[k]];
  return a / y - 1.0;
}

TEST(CloudReferenceError, AModelThatCompressesTheRangeShowsInTheQuarters) {
  const std::vector<double> truth = ramp(1);
  const CloudReferenceImage ref = referenceOf(truth, 0.0, 1);
  // a = sqrt(100 y): equal to y at y = 100, brighter below, darker above.
  std::vector<double> compressed;
  for (double y : truth) compressed.push_back(std::sqrt(100.0 * y));
  const CloudReferenceError e = compareWithCloudReference(imageOf(compressed), ref);
  // The quarters are y = 0.5..50 and 150.5..200: sum sqrt(100 y) / sum y - 1 over each.
  double darkA = 0.0, darkY = 0.0, brightA = 0.0, brightY = 0.0;
  for (int i = 1; i <= 100; ++i) darkA += std::sqrt(50.0 * i), darkY += 0.5 * i;
  for (int i = 301; i <= 400; ++i) brightA += std::sqrt(50.0 * i), brightY += 0.5 * i;
  EXPECT_NEAR(e.darkQuartileBias, darkA / darkY - 1.0, 1e-6);
  EXPECT_NEAR(e.brightQuartileBias, brightA / brightY - 1.0, 1e-6);
  EXPECT_GT(e.darkQuartileBias, 0.3);
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
  // A perfect fast path (a = the truth) against a reference whose halves have noise 20 each (the
  // whole: 14), 4000 pixels. The odd half's mean over the dark quarter (~1000 pixels, mean ~25) is
  // unbiased with a standard error of 20 / sqrt(1000) = 0.63, 2.5 %: the bound of 8 % is 3.2 of them.
  const std::vector<double> truth = ramp(10);
  const CloudReferenceImage ref = referenceOf(truth, 20.0, 3);
  const CloudReferenceError e = compareWithCloudReference(imageOf(truth), ref);
  EXPECT_LT(std::abs(e.darkQuartileBias), 0.08) << e.darkQuartileBias;
  EXPECT_LT(std::abs(e.brightQuartileBias), 0.08) << e.brightQuartileBias;
  // Split by the same (whole) reference that is measured, the perfect model looks too bright in the
  // dark quarter (regression to the mean): the bound above would fail.
  EXPECT_GT(darkQuarterBiasSplitBy(ref.luminance, truth, ref.luminance), 0.08);
}

TEST(CloudReferenceError, TheModelsOwnScatterDoesNotFakeAnExpandedRange) {
  // A model right on average at every brightness but off by +-30 % at random per pixel, against a
  // noiseless reference: the quarters split by the reference show no range error (each within 4 %;
  // the dark quarter's mean error has a standard error of ~0.3 / sqrt(3) / sqrt(1000), 0.5 %).
  const std::vector<double> truth = ramp(10);
  const CloudReferenceImage ref = referenceOf(truth, 0.0, 5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> scatter(-0.3, 0.3);
  std::vector<double> model;
  for (double y : truth) model.push_back(y * (1.0 + scatter(rng)));
  const CloudReferenceError e = compareWithCloudReference(imageOf(model), ref);
  EXPECT_LT(std::abs(e.darkQuartileBias), 0.04) << e.darkQuartileBias;
  EXPECT_LT(std::abs(e.brightQuartileBias), 0.04) << e.brightQuartileBias;
  // Split by the model's own luminance, its high draws land in the bright quarter and its low ones in
  // the dark: an expanded range that is not there.
  EXPECT_LT(darkQuarterBiasSplitBy(model, model, ref.luminance), -0.04);
}

TEST(CloudReferenceError, NoHalvesNoRange) {
  // A reference of one path per pixel has no halves: the quarters stay 0, the rest is computed.
  const std::vector<double> truth = ramp(1);
  CloudReferenceImage ref = referenceOf(truth, 0.0, 1);
  ref.luminanceEvenPaths.clear();
  ref.luminanceOddPaths.clear();
  std::vector<double> scaled;
  for (double y : truth) scaled.push_back(1.2 * y);
  const CloudReferenceError e = compareWithCloudReference(imageOf(scaled), ref);
  EXPECT_EQ(e.darkQuartileBias, 0.0);
  EXPECT_EQ(e.brightQuartileBias, 0.0);
  EXPECT_NEAR(e.meanBias, 0.2, 1e-6);
}

}  // namespace
}  // namespace firmament
