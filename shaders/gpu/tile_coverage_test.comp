#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: counts how often each pixel is visited by the tile dispatch (must be exactly once).
#include "common/dispatch.glsl"
layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(std430, binding = 0) buffer Counts { uint counts[]; };
layout(push_constant) uniform Push { TileDispatch tiles; } push;

void main() {
  uvec2 pixel;
  if (!tilePixel(push.tiles, pixel)) return;
  atomicAdd(counts[pixel.y * push.tiles.width + pixel.x], 1u);
}
