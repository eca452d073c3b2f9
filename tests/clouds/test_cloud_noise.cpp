// The noise textures: deterministic per seed, different across seeds, tileable, and the GPU bake
// equal to the shared procedural functions evaluated on the CPU in double.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "atmosphere/reference_random.h"
#include "clouds/blue_noise.h"
#include "clouds/cloud_noise.h"
#include "common/cloud_noise.glsl"
#include "gpu/command.h"
#include "tests/support/gpu_test.h"

namespace firmament {
namespace {

class CloudNoiseTest : public test::GpuTest {};

CloudNoiseSettings small() {
  CloudNoiseSettings s;
  s.shapeSize = 32;
  s.detailSize = 16;
  s.curlSize = 32;
  s.blueNoiseSize = 16;
  return s;
}

struct Baked {
  NoiseVolume shape, detail, curl;
};

Baked bake(uint32_t seed) {
  CloudNoise noise(test::GpuTest::context());
  gpu::CommandList commands(test::GpuTest::context());
  EXPECT_TRUE(noise.update(seed, small(), commands));
  commands.submitAndWait();
  gpu::CommandList again(test::GpuTest::context());
  EXPECT_FALSE(noise.update(seed, small(), again));  // cached by seed
  return {noise.downloadShape(), noise.downloadDetail(), noise.downloadCurl()};
}

TEST_F(CloudNoiseTest, DeterministicPerSeedAndDifferentAcrossSeeds) {
  Baked a = bake(7), b = bake(7), c = bake(8);
  EXPECT_EQ(a.shape.texels, b.shape.texels);
  EXPECT_EQ(a.detail.texels, b.detail.texels);
  EXPECT_EQ(a.curl.texels, b.curl.texels);
  EXPECT_NE(a.shape.texels, c.shape.texels);
  EXPECT_NE(a.detail.texels, c.detail.texels);
  EXPECT_NE(a.curl.texels, c.curl.texels);
  EXPECT_EQ(blueNoiseMask(16, 3), blueNoiseMask(16, 3));
  EXPECT_NE(blueNoiseMask(16, 3), blueNoiseMask(16, 4));
}

// GPU (float) bake vs the same shared functions in double, quantised to 8 bits like the texture:
// at most one step of 1/255 apart (rounding of values that fall near a quantisation boundary).
TEST_F(CloudNoiseTest, GpuBakeEqualsSharedFunctionsOnTheCpu) {
  Baked g = bake(11);
  reference::Random random(5, 0);
  int worst = 0;
  for (int k = 0; k < 300; ++k) {
    const int x = int(random.uniform() * 32), y = int(random.uniform() * 32), z = int(random.uniform() * 32);
    const glm::dvec4 cpu = shared::cloudShapeNoise((glm::dvec3(x, y, z) + 0.5) / 32.0, 11u);
    const glm::dvec4 gpu = g.shape.texel(x, y, z);
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, int(std::lround(std::abs(std::round(cpu[c] * 255.0) - gpu[c] * 255.0))));
    const int dx = x % 16, dy = y % 16, dz = z % 16;
    const glm::dvec4 cpuDetail = shared::cloudDetailNoise((glm::dvec3(dx, dy, dz) + 0.5) / 16.0, 11u);
    const glm::dvec4 gpuDetail = g.detail.texel(dx, dy, dz);
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, int(std::lround(std::abs(std::round(cpuDetail[c] * 255.0) - gpuDetail[c] * 255.0))));
  }
  EXPECT_LE(worst, 1);
}

// Tileable: f(p + one period) = f(p) for the shared functions (the lattice hashes are periodic
// exactly; only the rounding of p + 1 differs, hence 1e-12), and on the baked textures the
// step across the seam (last texel -> first) is no larger than between interior neighbours.
TEST_F(CloudNoiseTest, Tileable) {
  reference::Random random(9, 0);
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 p(random.uniform(), random.uniform(), random.uniform());
    for (const glm::dvec3& shift :
         {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 1, -1)}) {
      ASSERT_LT(glm::length(shared::cloudShapeNoise(p, 3u) - shared::cloudShapeNoise(p + shift, 3u)), 1e-12);
      ASSERT_LT(glm::length(shared::cloudDetailNoise(p, 3u) - shared::cloudDetailNoise(p + shift, 3u)), 1e-12);
    }
    const glm::dvec2 q(p.x, p.y);
    ASSERT_LT(
        glm::length(shared::cloudCurlNoise(q, 3u, 1e-3) - shared::cloudCurlNoise(q + glm::dvec2(1.0, -1.0), 3u, 1e-3)),
        1e-9);
  }
  Baked g = bake(3);
  for (int axis = 0; axis < 3; ++axis) {
    double seam = 0.0, interior = 0.0;
    const int n = g.shape.size;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        auto at = [&](int i) {
          glm::ivec3 t = axis == 0 ? glm::ivec3(i, a, b) : axis == 1 ? glm::ivec3(a, i, b) : glm::ivec3(a, b, i);
          return g.shape.texel(t.x, t.y, t.z);
        };
        seam += glm::length(at(n - 1) - at(0));
        interior += glm::length(at(n / 2 - 1) - at(n / 2));
      }
    std::printf("axis %d: mean step across the seam %.4f, between interior neighbours %.4f\n", axis, seam / (n * n),
                interior / (n * n));
    EXPECT_LT(seam, 1.5 * interior) << axis;
  }
}

// The mip chains (for the march's noise LOD): the shape and detail textures have levels down to 4^3,
// and every texel of level k is the mean of its 2x2x2 texels of level k - 1, to the 8-bit rounding of
// the result (half a step, 0.5/255, plus float slack).
TEST_F(CloudNoiseTest, MipLevelsAreBoxAverages) {
  CloudNoise noise(test::GpuTest::context());
  gpu::CommandList commands(test::GpuTest::context());
  noise.update(21u, small(), commands);
  commands.submitAndWait();
  for (const gpu::Image* image : {&noise.shape(), &noise.detail()}) {
    const uint32_t size = image->width();
    ASSERT_EQ(4u << (image->mipLevels() - 1), size) << image->desc().name;  // down to 4^3
    for (uint32_t level = 1; level < image->mipLevels(); ++level) {
      const std::vector<float> finer = image->downloadFloats(level - 1), coarser = image->downloadFloats(level);
      const int n = int(size >> level), m = 2 * n;
      ASSERT_EQ(coarser.size(), size_t(n) * n * n * 4);
      double worst = 0.0;
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x)
            for (int c = 0; c < 4; ++c) {
              double mean = 0.0;
              for (int i = 0; i < 8; ++i) {
                const int fx = 2 * x + (i & 1), fy = 2 * y + ((i >> 1) & 1), fz = 2 * z + (i >> 2);
                mean += finer[((size_t(fz) * m + fy) * m + fx) * 4 + c] / 8.0;
              }
              worst = std::max(worst, std::abs(coarser[((size_t(z) * n + y) * n + x) * 4 + c] - mean));
            }
      std::printf("%s level %u: largest |texel - mean of its 8| %.5f (1/255 = %.5f)\n", image->desc().name.c_str(),
                  level, worst, 1.0 / 255.0);
      EXPECT_LE(worst, 0.5 / 255.0 + 1e-4) << image->desc().name << " level " << level;
    }
  }
}

// Blue noise: every rank once (values uniform), and little low-frequency energy: the variance of 4x4
// box means is far below white noise's (1/12)/16.
TEST(BlueNoise, UniformRanksAndNoLowFrequencies) {
  const int n = 32;
  std::vector<float> mask = blueNoiseMask(n, 1);
  std::vector<float> sorted = mask;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < n * n; ++i) ASSERT_FLOAT_EQ(sorted[size_t(i)], float((i + 0.5) / (n * n)));
  double variance = 0.0;
  for (int by = 0; by < n; by += 4)
    for (int bx = 0; bx < n; bx += 4) {
      double mean = 0.0;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) mean += mask[size_t((by + y) * n + bx + x)] / 16.0;
      variance += (mean - 0.5) * (mean - 0.5);
    }
  variance /= double(n * n / 16);
  std::printf("blue noise: variance of 4x4 means %.2e (white noise %.2e)\n", variance, 1.0 / 12.0 / 16.0);
  EXPECT_LT(variance, 0.25 * (1.0 / 12.0 / 16.0));
}

// The disk cache (gpu::Context::cacheDir; the tests' context has a scratch folder): once a bake's
// commands ran, storeBaked writes it; a fresh CloudNoise (as in a later process) then uploads the same
// bits, records no bake pass, and rebuilds the same mip chains. A damaged file is ignored: baked again
// and rewritten.
TEST_F(CloudNoiseTest, DiskCacheGivesTheBakedBitsAndADamagedFileIsBakedAgain) {
  const uint32_t seed = 90210;  // no other test bakes it
  struct Run {
    std::string source;
    bool baked = false;  // a clouds/bake_noise_3d pass ran
    std::vector<float> shape, detail, curl, shapeLevel1;
  };
  auto run = [&]() {
    CloudNoise noise(context());
    gpu::CommandList commands(context());
    EXPECT_TRUE(noise.update(seed, small(), commands));
    commands.submitAndWait();
    noise.storeBaked();
    Run r;
    r.source = noise.source();
    for (const auto& t : commands.passTimings()) r.baked = r.baked || t.label == "clouds/bake_noise_3d";
    r.shape = noise.shape().downloadFloats();
    r.detail = noise.detail().downloadFloats();
    r.curl = noise.curl().downloadFloats();
    r.shapeLevel1 = noise.shape().downloadFloats(1);
    return r;
  };
  const std::filesystem::path folder = context().cacheDir() / "noise";
  auto files = [&]() {
    std::set<std::filesystem::path> names;
    if (std::filesystem::exists(folder))
      for (const auto& entry : std::filesystem::directory_iterator(folder)) names.insert(entry.path());
    return names;
  };
  const auto before = files();
  const Run first = run();
  EXPECT_EQ(first.source, "baked");
  EXPECT_TRUE(first.baked);
  std::vector<std::filesystem::path> added;
  for (const auto& f : files())
    if (!before.count(f)) added.push_back(f);
  ASSERT_EQ(added.size(), 1u);
  const auto size = std::filesystem::file_size(added[0]);

  const Run second = run();
  EXPECT_EQ(second.source, "disk cache");
  EXPECT_FALSE(second.baked);
  EXPECT_EQ(second.shape, first.shape);
  EXPECT_EQ(second.detail, first.detail);
  EXPECT_EQ(second.curl, first.curl);
  EXPECT_EQ(second.shapeLevel1, first.shapeLevel1);

  std::filesystem::resize_file(added[0], size / 2);  // damaged: cut short
  const Run third = run();
  EXPECT_EQ(third.source, "baked");
  EXPECT_TRUE(third.baked);
  EXPECT_EQ(third.shape, first.shape);
  EXPECT_EQ(std::filesystem::file_size(added[0]), size);  // rewritten whole
  EXPECT_EQ(run().source, "disk cache");
}

}  // namespace
}  // namespace firmament
