#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the tileable 2D curl texture from a seed (common/cloud_noise.glsl, cloudCurlNoise): RG = the
// curl of a periodic Perlin potential mapped to [0, 1]; finite differences over half a texel.
#include "common/cloud_noise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba8) uniform writeonly image2D curlImage;
layout(push_constant) uniform Push {
  int size;
  uint seed;
  int pad0;
  int pad1;
} push;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(push.size)))) return;
  vec2 uv = (vec2(texel) + 0.5) / float(push.size);
  imageStore(curlImage, texel, cloudCurlNoise(uv, push.seed, 0.5 / float(push.size)));
}
