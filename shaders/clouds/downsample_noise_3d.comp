#version 450
// One level of a 3D noise texture's mip chain (clouds/cloud_noise.cpp): texel p of level k is the mean
// of the 2x2x2 texels 2p .. 2p + 1 of level k - 1 (a box filter). The textures' sizes are powers of two
// and tile, so every level tiles too.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = 0, rgba8) uniform readonly image3D finer;     // level k - 1
layout(set = 0, binding = 1, rgba8) uniform writeonly image3D coarser;  // level k
layout(push_constant) uniform Push {
  int size;  // of level k
  int pad0;
  int pad1;
  int pad2;
} push;

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(texel, ivec3(push.size)))) return;
  vec4 sum = vec4(0.0);
  for (int i = 0; i < 8; ++i) sum += imageLoad(finer, 2 * texel + ivec3(i & 1, (i >> 1) & 1, i >> 2));
  imageStore(coarser, texel, 0.125 * sum);
}
