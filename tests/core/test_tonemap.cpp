// Exposure and tone maps: the analytic properties that docs/formats.md promises.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/tonemap.h"

namespace firmament {
namespace {

Image constantImage(float r, float g, float b, int width = 8, int height = 4) {
  Image image(width, height, 3);
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    image.pixels[3 * i] = r, image.pixels[3 * i + 1] = g, image.pixels[3 * i + 2] = b;
  }
  return image;
}

TEST(ToneMap, EveryCurveMapsZeroToZeroAndIsMonotonicAndBounded) {
  const float colours[][3] = {{1, 1, 1}, {1, 0.5f, 0.1f}, {0.02f, 0.1f, 1}, {0, 0, 1}, {1, 0, 0}};
  for (const std::string& name : toneMapNames()) {
    const ToneMap toneMap = parseToneMap(name);
    EXPECT_STREQ(toneMapName(toneMap), name.c_str());
    const float zero[3] = {0, 0, 0};
    float out[3];
    applyToneMap(toneMap, zero, out);
    EXPECT_EQ(out[0], 0.0f) << name;
    EXPECT_EQ(out[1], 0.0f) << name;
    EXPECT_EQ(out[2], 0.0f) << name;
    for (const auto& colour : colours) {
      float previous[3] = {0, 0, 0};
      // Tolerance: the inputs are float-rounded, so colour ratios jitter by an ulp on the plateau.
      for (double k = 1e-4; k < 1e4; k *= 1.05) {
        const float in[3] = {float(colour[0] * k), float(colour[1] * k), float(colour[2] * k)};
        applyToneMap(toneMap, in, out);
        for (int c = 0; c < 3; ++c) {
          EXPECT_GE(out[c], previous[c] - 1e-6f) << name << " k=" << k << " c=" << c;
          EXPECT_GE(out[c], 0.0f);
          EXPECT_LE(out[c], 1.0f);
          previous[c] = out[c];
        }
      }
    }
  }
}

TEST(ToneMap, AcesMatchesNarkowiczFit) {
  for (double x : {0.01, 0.18, 1.0, 3.0}) {
    const float in[3] = {float(x), float(x), float(x)};
    float out[3];
    applyToneMap(ToneMap::Aces, in, out);
    EXPECT_NEAR(out[1], x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 1e-6);
  }
}

TEST(ToneMap, ReinhardActsOnLuminanceAndKeepsHue) {
  const float in[3] = {0.4f, 0.2f, 0.1f};
  float out[3];
  applyToneMap(ToneMap::Reinhard, in, out);
  const double luminance = 0.2126 * 0.4 + 0.7152 * 0.2 + 0.0722 * 0.1;
  EXPECT_NEAR(out[0], 0.4 / (1 + luminance), 1e-6);
  EXPECT_NEAR(out[0] / out[1], 2.0, 1e-5);  // ratios (hue, saturation) unchanged
  EXPECT_NEAR(out[1] / out[2], 2.0, 1e-5);
  // A bright saturated blue exceeds 1 in B after L/(1+L); it is scaled back, not clipped per channel.
  const float blue[3] = {5.0f, 10.0f, 100.0f};
  applyToneMap(ToneMap::Reinhard, blue, out);
  EXPECT_FLOAT_EQ(out[2], 1.0f);
  EXPECT_NEAR(out[1] / out[2], 0.1, 1e-6);
}

TEST(ToneMap, UnknownNameIsInputErrorListingAllowedNames) {
  try {
    parseToneMap("filmic");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("filmic"), std::string::npos);
    for (const auto& name : toneMapNames()) EXPECT_NE(message.find(name), std::string::npos) << message;
  }
  ExposureSettings settings;
  settings.tonemap = "nope";
  EXPECT_THROW(toneMapToSrgb8(constantImage(1, 1, 1), settings), InputError);
}

TEST(Exposure, AutoEv100OfConstantImageIsAnalytic) {
  for (double luminance : {1e-3, 0.5, 1.0, 4000.0, 1.6e9}) {
    // Grey: Y equals each channel.
    EXPECT_NEAR(autoEv100(constantImage(float(luminance), float(luminance), float(luminance))),
                std::log2(luminance * 100.0 / 12.5), 1e-6)
        << luminance;
  }
  // A coloured constant image: Y = 0.2126 R + 0.7152 G + 0.0722 B.
  EXPECT_NEAR(autoEv100(constantImage(100, 200, 400)),
              std::log2((0.2126 * 100 + 0.7152 * 200 + 0.0722 * 400) * 8.0), 1e-6);
}

TEST(Exposure, AutoEv100IsTheLogAverage) {
  Image image = constantImage(1, 1, 1, 2, 1);
  image.at(1, 0)[0] = image.at(1, 0)[1] = image.at(1, 0)[2] = 16.0f;
  EXPECT_NEAR(autoEv100(image), std::log2(4.0 * 8.0), 1e-9);  // geometric mean of 1 and 16 is 4
}

TEST(Exposure, NonFinitePixelsAreSkippedAndCounted) {
  Image image = constantImage(2, 2, 2);
  image.at(0, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  image.at(3, 1)[2] = std::numeric_limits<float>::infinity();
  image.at(5, 2)[1] = -std::numeric_limits<float>::infinity();
  size_t skipped = 0;
  EXPECT_NEAR(autoEv100(image, &skipped), std::log2(16.0), 1e-9);
  EXPECT_EQ(skipped, 3u);
  EXPECT_NO_THROW(toneMapToSrgb8(image, ExposureSettings{}));
}

TEST(Exposure, BlackImageUsesTheLuminanceFloor) {
  EXPECT_NEAR(autoEv100(constantImage(0, 0, 0)), std::log2(kAutoExposureMinLuminance * 8.0), 1e-9);
}

TEST(Exposure, ScaleAndCompensation) {
  EXPECT_DOUBLE_EQ(exposureScale(0.0), 1.0 / 1.2);
  EXPECT_DOUBLE_EQ(exposureScale(3.0), 1.0 / 9.6);
  Image image = constantImage(0.3f, 0.3f, 0.3f);
  ExposureSettings settings;
  settings.mode = ExposureSettings::Mode::Fixed;
  settings.ev100 = 5.0;
  settings.compensationEv = 2.0;
  settings.tonemap = "clamp";
  double used = 0.0;
  const auto compensated = toneMapToSrgb8(image, settings, &used);
  EXPECT_DOUBLE_EQ(used, 3.0);
  settings.ev100 = 3.0;
  settings.compensationEv = 0.0;
  EXPECT_EQ(toneMapToSrgb8(image, settings), compensated);  // +2 EV at EV100 5 is EV100 3
}

TEST(Srgb, TransferFunctionAndQuantization) {
  EXPECT_EQ(srgbEncode(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgbEncode(0.002), 12.92 * 0.002);
  EXPECT_NEAR(srgbEncode(1.0), 1.0, 1e-12);
  EXPECT_NEAR(srgbEncode(0.18), 1.055 * std::pow(0.18, 1 / 2.4) - 0.055, 1e-12);
  // The two segments meet (continuity at the threshold to about 1e-7, as in the standard).
  EXPECT_NEAR(srgbEncode(0.0031308), srgbEncode(0.0031308 + 1e-12), 1e-6);
  EXPECT_EQ(srgbEncode(std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_EQ(quantize8(-1.0), 0);
  EXPECT_EQ(quantize8(0.5), 128);
  EXPECT_EQ(quantize8(2.0), 255);
}

}  // namespace
}  // namespace firmament
