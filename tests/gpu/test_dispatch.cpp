// The tile dispatch order (shaders/common/dispatch.glsl): a bijection from workgroups to tiles for
// every image size and order, checked on the CPU for the shared mapping and on the GPU by counting
// how often each pixel is written.
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/dispatch.h"
#include "gpu/pipeline.h"
#include "tests/support/gpu_test.h"

namespace firmament::gpu {
namespace {

struct Size {
  uint32_t width, height;
};
const Size kSizes[] = {{1, 1}, {7, 5}, {8, 8}, {9, 8}, {64, 64}, {100, 37}, {257, 129}, {640, 360}, {1000, 3}};

TEST(TileDispatchOrder, InterleavedStrideIsCoprimeAndFitsIn32Bits) {
  for (uint32_t count : {1u, 2u, 3u, 4u, 6u, 30u, 64u, 97u, 360u, 8160u, 65536u, 129600u, 1u << 20, 4000037u}) {
    uint32_t stride = interleavedStride(count);
    EXPECT_GE(stride, 1u);
    EXPECT_EQ(std::gcd(uint64_t(stride), uint64_t(count)), 1u) << count;
    EXPECT_LT(uint64_t(count - 1) * stride, uint64_t(1) << 32) << count;
    if (count >= 64 && count <= 65536) {
      EXPECT_NEAR(double(stride) / count, 0.618, 0.01) << count;
    }
  }
}

TEST(TileDispatchOrder, SharedMappingIsABijection) {
  for (Size size : kSizes)
    for (bool interleave : {false, true}) {
      TileDispatch tiles = tileDispatch(size.width, size.height, interleave, 65535);
      uint32_t count = shared::tileCount(tiles);
      std::vector<int> seen(count, 0);
      for (uint32_t group = 0; group < count; ++group) {
        glm::uvec2 tile = shared::tileOfGroup(tiles, group);
        ASSERT_LT(tile.x, shared::tileCountX(tiles));
        ASSERT_LT(tile.y, shared::tileCountY(tiles));
        ++seen[tile.y * shared::tileCountX(tiles) + tile.x];
      }
      for (int n : seen) ASSERT_EQ(n, 1) << size.width << "x" << size.height;
    }
}

TEST(TileDispatchOrder, InterleavingBalancesContiguousBlocks) {
  // Split the groups into T contiguous blocks as lavapipe does; each block should hold about half
  // top-half tiles (where a sky is expensive), not all or none as in row order.
  TileDispatch tiles = tileDispatch(1920, 1080, true, 65535);
  uint32_t count = shared::tileCount(tiles);
  for (uint32_t threads : {2u, 4u, 16u}) {
    for (uint32_t t = 0; t < threads; ++t) {
      uint32_t begin = count * t / threads, end = count * (t + 1) / threads, top = 0;
      for (uint32_t g = begin; g < end; ++g) top += shared::tileOfGroup(tiles, g).y < shared::tileCountY(tiles) / 2;
      EXPECT_NEAR(double(top) / (end - begin), 0.5, 0.05) << threads << " threads, block " << t;
    }
  }
}

class TileCoverageTest : public test::GpuTest {};

TEST_F(TileCoverageTest, EveryPixelWrittenExactlyOnce) {
  Context& gpu = context();
  ComputePipeline coverage(gpu, {.shader = "gpu/tile_coverage_test",
                                 .bindings = {BindingType::StorageBuffer},
                                 .pushConstantSize = sizeof(TileDispatch)});
  for (Size size : kSizes) {
    // Row order, interleaved, and a grid forced to wrap into rows of 5 groups (as past the device's
    // maxComputeWorkGroupCount[0]).
    TileDispatch variants[] = {tileDispatch(gpu, size.width, size.height, DispatchOrder::RowMajor),
                               tileDispatch(gpu, size.width, size.height, DispatchOrder::Interleaved),
                               tileDispatch(size.width, size.height, true, 5)};
    for (const TileDispatch& tiles : variants) {
      SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height) + " stride " +
                   std::to_string(tiles.stride) + " grid width " + std::to_string(tiles.gridWidth));
      std::vector<uint32_t> zeros(size_t(size.width) * size.height, 0);
      Buffer counts(gpu, zeros.size() * 4, BufferUsage::Storage, MemoryLocation::Device, "coverage");
      counts.upload(zeros);
      CommandList list(gpu);
      list.bind(coverage, {counts});
      list.pushConstants(tiles);
      list.dispatchTiles(tiles);
      list.submitAndWait();
      auto result = counts.download<uint32_t>();
      for (size_t i = 0; i < result.size(); ++i) ASSERT_EQ(result[i], 1u) << "pixel " << i;
    }
  }
}

TEST_F(TileCoverageTest, AutoOrderInterleavesOnlyOnTheCpu) {
  TileDispatch tiles = tileDispatch(context(), 640, 360);
  EXPECT_EQ(tiles.stride > 1u, context().isCpu());
}

}  // namespace
}  // namespace firmament::gpu
