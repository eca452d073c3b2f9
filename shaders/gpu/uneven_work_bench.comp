#version 460
#extension GL_GOOGLE_include_directive : require
// Benchmark kernel (bench/dispatch_order.cpp): a 2D image kernel whose top half costs `heavyIterations`
// of arithmetic per pixel and whose bottom half costs `lightIterations`, like sky above ground.
#include "common/dispatch.glsl"
layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(binding = 0, rgba16f) uniform writeonly image2D target;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  uint heavyIterations;
  uint lightIterations;
} push;

void main() {
  uvec2 pixel;
  if (!tilePixel(push.tiles, pixel)) return;
  uint iterations = pixel.y < push.tiles.height / 2u ? push.heavyIterations : push.lightIterations;
  vec2 z = vec2(pixel) / vec2(push.tiles.width, push.tiles.height);
  float sum = 0.0;
  for (uint k = 0u; k < iterations; ++k) {  // a cheap chaotic map the compiler cannot fold away
    z = vec2(sin(z.x * 3.1 + z.y), cos(z.y * 2.7 - z.x));
    sum += z.x * z.y;
  }
  imageStore(target, ivec2(pixel), vec4(z, sum, 1.0));
}
