#include "gpu/dispatch.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "gpu/context.h"

namespace firmament::gpu {

uint32_t interleavedStride(uint32_t tileCount) {
  if (tileCount <= 2) return 1;
  // 1/φ gives the most even coverage for every contiguous block of group indices (three-distance
  // theorem); the bound keeps group * stride inside 32 bits in the shader.
  constexpr double kInverseGoldenRatio = 0.6180339887498949;
  uint64_t limit = std::max<uint64_t>(1, 0xFFFFFFFFull / (tileCount - 1));
  uint64_t stride = std::min<uint64_t>(limit, uint64_t(std::llround(tileCount * kInverseGoldenRatio)));
  for (; stride > 1; --stride)
    if (std::gcd(stride, uint64_t(tileCount)) == 1) return uint32_t(stride);
  return 1;
}

TileDispatch tileDispatch(uint32_t width, uint32_t height, bool interleave, uint32_t maxGroupsX) {
  if (width == 0 || height == 0) throw RuntimeError("tileDispatch: empty image");
  TileDispatch tiles{};
  tiles.width = width;
  tiles.height = height;
  uint32_t count = shared::tileCount(tiles);
  tiles.stride = interleave ? interleavedStride(count) : 1u;
  tiles.gridWidth = std::min(count, std::max(1u, maxGroupsX));
  return tiles;
}

TileDispatch tileDispatch(const Context& context, uint32_t width, uint32_t height, DispatchOrder order) {
  bool interleave = order == DispatchOrder::Interleaved || (order == DispatchOrder::Auto && context.isCpu());
  return tileDispatch(width, height, interleave, context.limits().maxComputeWorkGroupCount[0]);
}

GroupCount tileGroupCount(const TileDispatch& tiles) {
  uint32_t count = shared::tileCount(tiles);
  return {tiles.gridWidth, (count + tiles.gridWidth - 1) / tiles.gridWidth};
}

}  // namespace firmament::gpu
