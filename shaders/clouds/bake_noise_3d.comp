#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes one tileable 3D cloud noise texture from a seed (common/cloud_noise.glsl): the shape texture
// (kind 0, Perlin-Worley + three Worley octaves) or the detail texture (kind 1, four Worley octaves).
// Texel i holds the noise at its centre (i + 0.5) / size, so a linear, repeating sampler returns the
// function's values at texel centres and interpolates between them, across the seam too.
#include "common/cloud_noise.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = 0, rgba8) uniform writeonly image3D noiseImage;
layout(push_constant) uniform Push {
  int size;
  uint seed;
  int kind;
  int pad;
} push;

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(texel, ivec3(push.size)))) return;
  vec3 uvw = (vec3(texel) + 0.5) / float(push.size);
  vec4 value = push.kind == 0 ? cloudShapeNoise(uvw, push.seed) : cloudDetailNoise(uvw, push.seed);
  imageStore(noiseImage, texel, value);
}
