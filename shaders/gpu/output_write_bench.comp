#version 460
#extension GL_GOOGLE_include_directive : require
// Benchmark kernel (bench/output_write.cpp): what writing one RGBA32F pixel costs, by target.
// mode 0: nothing is written; 1: imageStore to a storage image; 2: a vec4 store to a storage buffer
// (row-major, one vec4 per pixel). A little arithmetic keeps the store from being folded away.
#include "common/dispatch.glsl"
layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(binding = 0, rgba32f) uniform writeonly image2D targetImage;
layout(std430, binding = 1) writeonly buffer TargetBuffer { vec4 pixels[]; } targetBuffer;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  uint mode;
} push;

void main() {
  uvec2 pixel;
  if (!tilePixel(push.tiles, pixel)) return;
  vec4 value = vec4(vec2(pixel) / vec2(push.tiles.width, push.tiles.height), 0.5, 1.0);
  if (push.mode == 1u) imageStore(targetImage, ivec2(pixel), value);
  else if (push.mode == 2u) targetBuffer.pixels[pixel.y * push.tiles.width + pixel.x] = value;
}
