#pragma once
// Parameters for 2D image kernels written with shaders/common/dispatch.glsl: which tile each workgroup
// shades. Interleaved order balances uneven work across lavapipe's threads; row order keeps cache
// locality on GPUs. See docs/gpu.md for the measurements.
#include <cstdint>

#include "common/dispatch.glsl"

namespace firmament::gpu {

class Context;

using TileDispatch = shared::TileDispatch;
inline constexpr uint32_t kTileSize = FIRMAMENT_TILE_SIZE;

enum class DispatchOrder {
  Auto,         // Interleaved on CPU devices (lavapipe), RowMajor on GPUs
  RowMajor,     // stride 1
  Interleaved,  // stride near tileCount / golden ratio, coprime with tileCount
};

// The tile dispatch for a width × height image on this device.
TileDispatch tileDispatch(const Context& context, uint32_t width, uint32_t height,
                          DispatchOrder order = DispatchOrder::Auto);
// The same without a device: `interleave` picks the order, `maxGroupsX` is the device's
// maxComputeWorkGroupCount[0] (the grid wraps into rows past it).
TileDispatch tileDispatch(uint32_t width, uint32_t height, bool interleave, uint32_t maxGroupsX);

// A stride coprime with tileCount, near tileCount / golden ratio, with (tileCount - 1) * stride < 2^32.
uint32_t interleavedStride(uint32_t tileCount);

struct GroupCount {
  uint32_t x = 1;
  uint32_t y = 1;
};
// The vkCmdDispatch grid for `tiles` (what CommandList::dispatchTiles uses).
GroupCount tileGroupCount(const TileDispatch& tiles);

}  // namespace firmament::gpu
