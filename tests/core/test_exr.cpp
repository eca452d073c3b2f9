// EXR I/O: bit-exact float round trips with metadata, half files, and clear errors for bad files.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/exr_io.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {
namespace fs = std::filesystem;

// Values that a lossy or half path would change: extremes, denormals, signed zero, many mantissa bits.
Image makeTestImage(int width, int height, int channels) {
  Image image(width, height, channels);
  const float specials[] = {0.0f,
                            -0.0f,
                            1.0f,
                            3.14159274f,
                            1e-40f /* denormal */,
                            6.5e4f,
                            1.7e38f,
                            -2.5f,
                            1.0f / 3.0f,
                            123456.789f,
                            std::numeric_limits<float>::min()};
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = i < std::size(specials) ? specials[i] : std::sin(float(i) * 0.37f) * float(i) * 1.001f;
  return image;
}

void expectBitExact(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
}

void expectInputErrorNaming(const fs::path& path, const std::string& reason) {
  try {
    readExr(path);
    FAIL() << "expected InputError for " << path;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
  }
}

class ExrRoundTrip : public ::testing::TestWithParam<std::tuple<int, ExrCompression>> {};

TEST_P(ExrRoundTrip, FloatPixelsAndMetadataAreBitExact) {
  const auto [channels, compression] = GetParam();
  Image image = makeTestImage(37, 23, channels);  // odd sizes exercise partial blocks of PIZ/ZIP
  image.metadata["firmament.scene_hash"] = "9f2c4e1a";
  image.metadata["firmament.device"] = "llvmpipe (LLVM 15.0.6, 256 bits)";
  image.metadata["firmament.timing.sky_ms"] = "12.5";
  image.metadata["firmament.sun_direction"] = "[0.1, 0.7, -0.2]";
  image.metadata["firmament.empty"] = "";
  const fs::path path =
      test::scratchDir("exr_roundtrip_" + std::to_string(channels) + "_" + std::to_string(int(compression))) /
      "image.exr";
  writeExr(path, image, compression);
  const Image back = readExr(path);
  expectBitExact(image, back);
  for (const auto& [key, value] : image.metadata) {
    ASSERT_TRUE(back.metadata.count(key)) << key;
    EXPECT_EQ(back.metadata.at(key), value) << key;
  }
}

INSTANTIATE_TEST_SUITE_P(ChannelsAndCompression, ExrRoundTrip,
                         ::testing::Combine(::testing::Values(3, 4),
                                            ::testing::Values(ExrCompression::Zip, ExrCompression::Piz)));

TEST(Exr, NanAndInfinitySurviveRoundTrip) {
  Image image(2, 1, 3);
  image.pixels = {std::numeric_limits<float>::quiet_NaN(),
                  std::numeric_limits<float>::infinity(),
                  -std::numeric_limits<float>::infinity(),
                  1,
                  2,
                  3};
  const fs::path path = test::scratchDir("exr_nan") / "nan.exr";
  writeExr(path, image);
  const Image back = readExr(path);
  EXPECT_TRUE(std::isnan(back.pixels[0]));
  EXPECT_EQ(back.pixels[1], std::numeric_limits<float>::infinity());
  EXPECT_EQ(back.pixels[2], -std::numeric_limits<float>::infinity());
  EXPECT_EQ(back.pixels[5], 3.0f);
}

TEST(Exr, ReadsHalfChannelsIgnoresExtraChannelsAndHonoursDataWindow) {
  // Written directly with OpenEXR: half R, G, B and a float Z, data window not at the origin.
  const int width = 5, height = 3;
  const Imath::Box2i window(Imath::V2i(10, 20), Imath::V2i(10 + width - 1, 20 + height - 1));
  Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(63, 63)), window);
  header.compression() = Imf::PIZ_COMPRESSION;
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::HALF));
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  header.insert("comment", Imf::StringAttribute("written as half"));
  std::vector<half> rgb(size_t(width * height * 3));
  std::vector<float> z(size_t(width * height), 7.0f);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = half(float(i) * 0.25f + 0.5f);  // exact in half
  const fs::path path = test::scratchDir("exr_half") / "half.exr";
  {
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c)
      frame.insert(c == 0   ? "R"
                   : c == 1 ? "G"
                            : "B",
                   Imf::Slice::Make(Imf::HALF, rgb.data() + c, window, 3 * sizeof(half), 3 * sizeof(half) * width));
    frame.insert("Z", Imf::Slice::Make(Imf::FLOAT, z.data(), window, sizeof(float), sizeof(float) * width));
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }
  const Image image = readExr(path);
  EXPECT_EQ(image.width, width);
  EXPECT_EQ(image.height, height);
  EXPECT_EQ(image.channels, 3);
  for (size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(image.pixels[i], float(i) * 0.25f + 0.5f) << i;
  EXPECT_EQ(image.metadata.at("comment"), "written as half");
}

TEST(Exr, MissingFileIsInputErrorNamingIt) {
  expectInputErrorNaming(test::scratchDir("exr_missing") / "does_not_exist.exr", "no such file");
}

TEST(Exr, NonExrFileIsInputErrorNamingIt) {
  const fs::path path = test::scratchDir("exr_text") / "not_an_image.exr";
  std::ofstream(path) << "this is plain text, not OpenEXR\n";
  expectInputErrorNaming(path, "not an OpenEXR file");
}

TEST(Exr, TruncatedFileIsInputErrorNamingIt) {
  const fs::path dir = test::scratchDir("exr_truncated");
  const fs::path full = dir / "full.exr", cut = dir / "cut.exr";
  writeExr(full, makeTestImage(64, 64, 4));
  fs::copy_file(full, cut);
  fs::resize_file(cut, fs::file_size(full) / 2);
  try {
    readExr(cut);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(cut.string()), std::string::npos) << e.what();
  }
}

TEST(Exr, FileWithoutRgbIsInputErrorListingChannels) {
  Imf::Header header(4, 4);
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  std::vector<float> z(16, 1.0f);
  const fs::path path = test::scratchDir("exr_depth") / "depth.exr";
  {
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float), 4 * sizeof(float)));
    file.setFrameBuffer(frame);
    file.writePixels(4);
  }
  expectInputErrorNaming(path, "Z");
}

TEST(Exr, ReservedMetadataKeyIsRejectedAndNothingIsWritten) {
  Image image(2, 2, 3);
  image.metadata["compression"] = "none";
  const fs::path path = test::scratchDir("exr_reserved") / "reserved.exr";
  EXPECT_THROW(writeExr(path, image), RuntimeError);
  EXPECT_FALSE(fs::exists(path));
}

TEST(Exr, WriteIntoMissingFolderIsInputError) {
  EXPECT_THROW(writeExr(test::scratchDir("exr_nofolder") / "missing" / "a.exr", Image(2, 2, 3)), InputError);
}

}  // namespace
}  // namespace firmament
