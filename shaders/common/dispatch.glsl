// dispatch.glsl: the order in which a 2D image kernel visits its 8×8-pixel tiles. Shared with C++
// (gpu/dispatch.h) so the host picks the parameters and the tests check the mapping on both sides.
//
// Why: lavapipe hands each CPU thread one contiguous block of workgroup indices. A sky image costs far
// more above the horizon than below it, so in row order one thread gets all the sky and the others
// idle. The kernel therefore runs as a 1D grid of N = tilesX * tilesY groups and visits tile
// (i * stride) mod N for group i: with stride coprime to N this is a permutation, and with stride near
// N / golden ratio every contiguous block of i samples the whole image evenly (a Weyl sequence).
// stride = 1 is plain row order, the better choice on GPUs, where neighbouring groups share caches.
//
// Use in a shader:
//   #include "common/dispatch.glsl"
//   layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
//   layout(push_constant) uniform Push { TileDispatch tiles; /* the pass's own fields */ } push;
//   void main() { uvec2 pixel; if (!tilePixel(push.tiles, pixel)) return; ... }
// and on the host: CommandList::dispatchTiles(push.tiles) with push.tiles = tileDispatch(...).
#ifndef FIRMAMENT_DISPATCH_GLSL
#define FIRMAMENT_DISPATCH_GLSL

#include "common/compat.glsl"

#define FIRMAMENT_TILE_SIZE 8

SHARED_BEGIN

// 16 bytes, at offset 0 of the kernel's push constants (same layout in std430 and C++).
struct TileDispatch {
  uint width;      // image size in pixels
  uint height;
  uint stride;     // coprime with tileCount; 1 = row order. (tileCount - 1) * stride < 2^32.
  uint gridWidth;  // groups per row of the dispatch grid (the grid is 2D only past the device's
                   // maxComputeWorkGroupCount[0]); extra groups in the last row do nothing
};

SHARED_INLINE uint tileCountX(TileDispatch d) { return (d.width + uint(FIRMAMENT_TILE_SIZE) - 1u) / uint(FIRMAMENT_TILE_SIZE); }
SHARED_INLINE uint tileCountY(TileDispatch d) { return (d.height + uint(FIRMAMENT_TILE_SIZE) - 1u) / uint(FIRMAMENT_TILE_SIZE); }
SHARED_INLINE uint tileCount(TileDispatch d) { return tileCountX(d) * tileCountY(d); }

// The tile (column, row) that workgroup number `group` (< tileCount) works on.
SHARED_INLINE uvec2 tileOfGroup(TileDispatch d, uint group) {
  uint tile = (group * d.stride) % tileCount(d);
  uint columns = tileCountX(d);
  return uvec2(tile % columns, tile / columns);
}

SHARED_END

#ifndef __cplusplus
// The pixel this invocation shades; false for invocations past the image edge or past the last tile.
bool tilePixel(TileDispatch d, out uvec2 pixel) {
  uint group = gl_WorkGroupID.y * d.gridWidth + gl_WorkGroupID.x;
  pixel = uvec2(0u);
  if (group >= tileCount(d)) return false;
  pixel = tileOfGroup(d, group) * uint(FIRMAMENT_TILE_SIZE) + gl_LocalInvocationID.xy;
  return pixel.x < d.width && pixel.y < d.height;
}
#endif

#endif  // FIRMAMENT_DISPATCH_GLSL
