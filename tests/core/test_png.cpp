// PNG previews: read back with libpng itself and checked against the formulas of docs/formats.md,
// computed here independently of core/tonemap.cpp.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/png_io.h"
#include "core/tonemap.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {
namespace fs = std::filesystem;

// The reference formulas (docs/formats.md), written out again on purpose.
double srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }
uint8_t byteOf(double displayLinear) { return uint8_t(std::lround(255.0 * srgb(std::clamp(displayLinear, 0.0, 1.0)))); }
double aces(double x) { return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

struct LibpngImage {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
};

LibpngImage readWithLibpng(const fs::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_file(&image, path.c_str())) << image.message;
  LibpngImage out;
  out.width = int(image.width);
  out.height = int(image.height);
  out.channels = int(PNG_IMAGE_SAMPLE_CHANNELS(image.format));
  image.format = out.channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  out.channels = int(PNG_IMAGE_SAMPLE_CHANNELS(image.format));
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr)) << image.message;
  return out;
}

TEST(Png, RawRoundTripThroughLibpng) {
  const int width = 7, height = 5;
  std::vector<uint8_t> rgba(size_t(width * height * 4));
  for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = uint8_t(i * 37 + 11);
  const fs::path path = test::scratchDir("png_raw") / "raw.png";
  writePng(path, width, height, 4, rgba.data(), {{"Comment", "hello"}});
  const LibpngImage back = readWithLibpng(path);
  EXPECT_EQ(back.width, width);
  EXPECT_EQ(back.height, height);
  ASSERT_EQ(back.channels, 4);
  EXPECT_EQ(back.pixels, rgba);
  const Image8 ours = readPng(path);
  EXPECT_EQ(ours.pixels, rgba);
  EXPECT_EQ(ours.text.at("Comment"), "hello");
}

TEST(Png, PreviewWithFixedExposureMatchesFormulas) {
  // EV100 = 0 → exposure scale 1/1.2. Pixel values chosen so that exposed values are simple.
  Image image(3, 2, 3);
  auto set = [&](int x, int y, float r, float g, float b) {
    float* p = image.at(x, y);
    p[0] = r, p[1] = g, p[2] = b;
  };
  set(0, 0, 0.6f, 0.6f, 0.6f);      // exposed 0.5
  set(1, 0, 0.0f, 0.0f, 0.0f);      // black stays black
  set(2, 0, 12.0f, 12.0f, 12.0f);   // exposed 10 → clipped
  set(0, 1, 0.0012f, 0.06f, 1.2f);  // exposed 0.001 (linear segment of sRGB), 0.05, 1
  set(1, 1, -1.0f, 0.3f, 0.3f);     // negative radiance taken as 0
  set(2, 1, 0.24f, 0.24f, 0.24f);   // exposed 0.2
  ExposureSettings settings;
  settings.mode = ExposureSettings::Mode::Fixed;
  settings.ev100 = 0.0;
  settings.tonemap = "clamp";
  const fs::path path = test::scratchDir("png_preview") / "preview.png";
  EXPECT_DOUBLE_EQ(writePngPreview(path, image, settings), 0.0);

  const LibpngImage png = readWithLibpng(path);
  ASSERT_EQ(png.width, 3);
  ASSERT_EQ(png.height, 2);
  ASSERT_EQ(png.channels, 3);
  auto px = [&](int x, int y, int c) { return png.pixels[size_t((y * 3 + x) * 3 + c)]; };
  const double exposure = 1.0 / 1.2;
  EXPECT_EQ(px(0, 0, 0), byteOf(0.6 * exposure));
  EXPECT_EQ(px(0, 0, 0), 188);  // 255 · (1.055 · 0.5^(1/2.4) − 0.055) = 187.52
  EXPECT_EQ(px(1, 0, 1), 0);
  EXPECT_EQ(px(2, 0, 2), 255);
  EXPECT_EQ(px(0, 1, 0), byteOf(0.0012 * exposure));
  EXPECT_EQ(px(0, 1, 0), 3);  // 255 · 12.92 · 0.001 = 3.29
  EXPECT_EQ(px(0, 1, 1), byteOf(0.06 * exposure));
  EXPECT_EQ(px(0, 1, 2), 255);
  EXPECT_EQ(px(1, 1, 0), 0);
  EXPECT_EQ(px(2, 1, 1), byteOf(0.24 * exposure));

  const Image8 ours = readPng(path);
  EXPECT_EQ(ours.text.at("firmament.tonemap"), "clamp");
  EXPECT_EQ(std::stod(ours.text.at("firmament.ev100")), 0.0);
}

TEST(Png, AutoExposureOfConstantImageWithAces) {
  // Auto exposure of a constant luminance L: EV100 = log2(8 L), so the exposed value is
  // L / (1.2 · 8 L) = 1/9.6 whatever L is; +1 EV of compensation doubles it.
  for (double luminance : {0.05, 3.0, 8000.0}) {
    Image image(4, 4, 4);
    for (size_t i = 0; i < image.pixelCount(); ++i) {
      float* p = image.pixels.data() + 4 * i;
      p[0] = p[1] = p[2] = float(luminance);
      p[3] = 0.5f;
    }
    ExposureSettings settings;       // auto, aces
    settings.nightAdaptation = 1.0;  // the plain meter also below 5 cd/m² (tests/core/test_tonemap.cpp: NightExposure)
    settings.compensationEv = 1.0;
    settings.keepAlpha = true;
    const fs::path path = test::scratchDir("png_auto") / "auto.png";
    const double ev = writePngPreview(path, image, settings);
    EXPECT_NEAR(ev, std::log2(8.0 * double(float(luminance))) - 1.0, 1e-9);  // the pixels are float
    const LibpngImage png = readWithLibpng(path);
    ASSERT_EQ(png.channels, 4);
    EXPECT_EQ(png.pixels[5], byteOf(aces(2.0 / 9.6))) << luminance;
    EXPECT_EQ(png.pixels[7], 128);  // alpha 0.5, linear: round(127.5)
  }
}

TEST(Png, NonFinitePixelsAreMagentaAndDoNotPoisonExposure) {
  Image image(3, 1, 3);
  std::fill(image.pixels.begin(), image.pixels.end(), 2.0f);
  image.at(1, 0)[1] = std::numeric_limits<float>::quiet_NaN();
  image.at(2, 0)[0] = std::numeric_limits<float>::infinity();
  const fs::path path = test::scratchDir("png_nan") / "nan.png";
  ExposureSettings settings;
  settings.nightAdaptation = 1.0;  // the plain meter at 2 cd/m²
  const double ev = writePngPreview(path, image, settings);
  EXPECT_NEAR(ev, std::log2(8.0 * 2.0), 1e-9);
  const LibpngImage png = readWithLibpng(path);
  EXPECT_EQ(png.pixels[3], 255);
  EXPECT_EQ(png.pixels[4], 0);
  EXPECT_EQ(png.pixels[5], 255);
  EXPECT_EQ(png.pixels[0], byteOf(aces(1.0 / 9.6)));
}

TEST(Png, ReadingBadFilesIsInputErrorNamingTheFile) {
  const fs::path dir = test::scratchDir("png_bad");
  const fs::path text = dir / "text.png";
  std::ofstream(text) << "not a png at all";
  for (const fs::path& path : {dir / "missing.png", text}) {
    try {
      readPng(path);
      FAIL() << "expected InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace firmament
