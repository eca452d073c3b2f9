#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: a 2D image kernel through the tile dispatch; texel (x, y) = (x, y, x + width * y, base).
#include "common/dispatch.glsl"
layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(binding = 0, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  float base;
} push;

void main() {
  uvec2 pixel;
  if (!tilePixel(push.tiles, pixel)) return;
  imageStore(target, ivec2(pixel), vec4(pixel.x, pixel.y, pixel.x + push.tiles.width * pixel.y, push.base));
}
