// Exposure and tone maps: the analytic properties that docs/formats.md promises.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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
  EXPECT_NEAR(autoEv100(constantImage(100, 200, 400)), std::log2((0.2126 * 100 + 0.7152 * 200 + 0.0722 * 400) * 8.0),
              1e-6);
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

// ---- Night: the automatic exposure's adaptation, its limits, the eye's time constants, mesopic vision ----

namespace firmament {
namespace {

TEST(NightExposure, DaylightExposureIsTheMetersUnchanged) {
  // At and above 5 cd/m² the automatic EV100 is log2(8 L), bit for bit what autoEv100 gives.
  ExposureSettings settings;
  for (double luminance : {5.0, 6.0, 120.0, 4500.0, 2.0e5}) {
    const Image image = constantImage(float(luminance), float(luminance), float(luminance));
    EXPECT_EQ(autoEv100ForLuminance(logAverageLuminance(image), settings), autoEv100(image)) << luminance;
    EXPECT_NEAR(autoEv100ForLuminance(luminance, settings), std::log2(8.0 * luminance), 1e-12);
  }
}

TEST(NightExposure, BelowTheMesopicTopTheExposureMakesUpOnlyPartOfTheFall) {
  ExposureSettings settings;  // night_adaptation 0.8
  const double knee = std::log2(8.0 * kNightAdaptationLuminance);
  // A moonless night (2e-4 cd/m², Leinert's dark sky) ends 0.2 x log2(5 / 2e-4) = 2.92 stops darker than
  // a full adaptation would show it; a full-moon sky (~7e-3 cd/m²) 1.90 stops.
  for (double luminance : {2e-4, 7e-3, 0.5}) {
    const double full = std::log2(8.0 * luminance);
    const double ev = autoEv100ForLuminance(luminance, settings);
    EXPECT_NEAR(ev, knee + 0.8 * (full - knee), 1e-12);
    std::printf("L %.0e cd/m^2: EV100 %.2f (full adaptation %.2f, %.2f stops darker)\n", luminance, ev, full,
                ev - full);
  }
  EXPECT_NEAR(autoEv100ForLuminance(2e-4, settings) - std::log2(8.0 * 2e-4), 0.2 * std::log2(5.0 / 2e-4), 1e-12);
  // Continuous at the knee and non-decreasing everywhere.
  EXPECT_NEAR(autoEv100ForLuminance(kNightAdaptationLuminance * (1 - 1e-9), settings), knee, 1e-8);
  double previous = -1e9;
  for (double logL = -7.0; logL <= 6.0; logL += 0.01) {
    const double ev = autoEv100ForLuminance(std::pow(10.0, logL), settings);
    EXPECT_GE(ev, previous);
    previous = ev;
  }
  // night_adaptation 1 is the plain meter; 0 freezes the exposure at the knee.
  settings.nightAdaptation = 1.0;
  EXPECT_NEAR(autoEv100ForLuminance(1e-3, settings), std::log2(8e-3), 1e-12);
  settings.nightAdaptation = 0.0;
  EXPECT_NEAR(autoEv100ForLuminance(1e-3, settings), knee, 1e-12);
}

TEST(NightExposure, LimitsClampTheAutomaticExposure) {
  ExposureSettings settings;
  settings.ev100Min = -4.0;
  settings.ev100Max = 12.0;
  EXPECT_DOUBLE_EQ(autoEv100ForLuminance(1e-5, settings), -4.0);
  EXPECT_DOUBLE_EQ(autoEv100ForLuminance(1e5, settings), 12.0);
  settings.compensationEv = 1.0;
  double used = 0.0;
  toneMapToSrgb8(constantImage(1e-5f, 1e-5f, 1e-5f), settings, &used);
  EXPECT_DOUBLE_EQ(used, -5.0);  // compensation applies after the limit
  settings.ev100Min = 13.0;
  EXPECT_THROW(toneMapToSrgb8(constantImage(1, 1, 1), settings), InputError);
}

TEST(NightExposure, EyeTimeConstantsBlendRodsAndCones) {
  // Krawczyk et al. 2005: sigma = 0.04 / (0.04 + L); tau = sigma 0.4 s + (1 - sigma) 0.1 s.
  EXPECT_DOUBLE_EQ(rodSensitivity(0.04), 0.5);
  EXPECT_NEAR(eyeAdaptationTimeConstant(0.04), 0.25, 1e-12);
  EXPECT_NEAR(eyeAdaptationTimeConstant(1e-6), 0.4, 1e-5);
  EXPECT_NEAR(eyeAdaptationTimeConstant(1e4), 0.1, 1e-5);
}

TEST(NightExposure, TemporalAdaptationIsAnExponentialInLogLuminance) {
  ExposureSettings settings;
  settings.temporal = ExposureSettings::TemporalAdaptation::Exponential;
  settings.adaptationTimeSeconds = 2.0;
  ExposureAdaptation adaptation;
  EXPECT_DOUBLE_EQ(adaptation.update(100.0, 0.0, settings), 100.0);  // the first frame starts adapted
  // A step from 100 to 1 cd/m²: after one time constant the log luminance has gone 1 - 1/e of the way,
  // in any number of frames (the filter composes exactly), never past the target.
  double adapted = 0.0;
  for (int i = 0; i < 60; ++i) adapted = adaptation.update(1.0, 2.0 / 60.0, settings);
  EXPECT_NEAR(std::log(adapted), std::log(100.0) * std::exp(-1.0), 1e-9);
  for (int i = 0; i < 2000; ++i) {
    adapted = adaptation.update(1.0, 0.1, settings);
    EXPECT_GE(adapted, 1.0);
  }
  EXPECT_NEAR(adapted, 1.0, 1e-9);
  // Frame-to-frame noise of +-20 % around a constant level is damped 20x at 30 frames/s, tau 1 s (a first-order
  // filter passes (1 - k) / (1 + k) of an alternating signal, k = exp(-1/30)): measured +-0.91 %.
  settings.adaptationTimeSeconds = 1.0;
  ExposureAdaptation noisy;
  double worst = 0.0;
  for (int i = 0; i < 300; ++i) {
    const double l = noisy.update(i % 2 ? 1.2 : 1.0 / 1.2, 1.0 / 30.0, settings);
    if (i > 100) worst = std::max(worst, std::abs(std::log(l)));
  }
  std::printf("flicker of a +-20 %% alternating luminance after the filter: +-%.2f %%\n", 100 * (std::exp(worst) - 1));
  EXPECT_LT(worst, std::log(1.2) / 15.0);
  // None meters every frame alone; the eye's time constant follows the adapted level.
  settings.temporal = ExposureSettings::TemporalAdaptation::None;
  EXPECT_DOUBLE_EQ(noisy.update(42.0, 1.0 / 30.0, settings), 42.0);
  settings.temporal = ExposureSettings::TemporalAdaptation::Eye;
  ExposureAdaptation eye;
  eye.update(1e-4, 0.0, settings);
  EXPECT_NEAR(std::log(eye.update(1.0, 0.4, settings) / 1.0),
              std::log(1e-4) * std::exp(-0.4 / eyeAdaptationTimeConstant(1e-4)), 1e-9);
}

TEST(NightExposure, ScotopicLuminanceFollowsLarsonRushmeierPiatko) {
  // V = Y (1.33 (1 + (Y + Z) / X) - 1.68): D65 white (X 0.9505, Z 1.089 at Y 1) gives 2.57, illuminant A
  // (X 1.0985, Z 0.3558) 1.29: bluish light is brighter to the rods (published S/P ratios: D65 2.47, A 1.41).
  EXPECT_NEAR(scotopicLuminance(0.9505, 1.0, 1.089), 1.33 * (1.0 + 2.089 / 0.9505) - 1.68, 1e-12);
  EXPECT_NEAR(scotopicLuminance(0.9505, 1.0, 1.089), 2.47, 0.15);
  EXPECT_NEAR(scotopicLuminance(1.0985, 1.0, 0.3558), 1.41, 0.15);
  EXPECT_DOUBLE_EQ(scotopicLuminance(0.0, 1.0, 1.0), 0.0);
}

TEST(NightExposure, MesopicVisionFadesColourIntoBlueAtNightAndKeepsDaylight) {
  // Daylight: unchanged to float precision (rods' share 8e-6 at 5000 cd/m²).
  float day[3] = {4000.0f, 5000.0f, 6000.0f};
  applyMesopicVision(day);
  EXPECT_NEAR(day[0], 4000.0f, 0.5f);
  EXPECT_NEAR(day[2], 6000.0f, 0.5f);
  // A red pixel at night turns into a dim blue-grey: the rods barely see red.
  float red[3] = {1e-3f, 1e-4f, 1e-4f};
  applyMesopicVision(red);
  EXPECT_GT(red[2], red[0]);
  // A white pixel at 1e-4 cd/m² is shown at its scotopic luminance in the blue of chromaticity (0.25, 0.25).
  float white[3] = {1e-4f, 1e-4f, 1e-4f};
  applyMesopicVision(white);
  const double y = 0.2126 * white[0] + 0.7152 * white[1] + 0.0722 * white[2];
  const double x = 0.4124 * white[0] + 0.3576 * white[1] + 0.1805 * white[2];
  const double z = 0.0193 * white[0] + 0.1192 * white[1] + 0.9505 * white[2];
  EXPECT_NEAR(x / (x + y + z), 0.25, 0.01);
  EXPECT_NEAR(y / 1e-4, 2.5, 0.2);  // V/Y of D65 (rods' share 0.9975)
  // The preview only changes where asked: photopic (the default) leaves a night image as it was.
  ExposureSettings photopic, mesopic;
  mesopic.vision = ExposureSettings::Vision::Mesopic;
  const Image night = constantImage(2e-3f, 1e-3f, 1e-3f);
  EXPECT_NE(toneMapToSrgb8(night, photopic), toneMapToSrgb8(night, mesopic));
  const Image noon = constantImage(3000.0f, 3000.0f, 3000.0f);
  EXPECT_EQ(toneMapToSrgb8(noon, photopic), toneMapToSrgb8(noon, mesopic));
}

}  // namespace
}  // namespace firmament
