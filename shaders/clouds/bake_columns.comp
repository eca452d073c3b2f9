#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the column map (clouds/column_map.glsl): per texel and layer, the column's optical depth from
// each of its K + 1 levels up to the layer top, one midpoint sample of the full density per level
// segment (K per column), at the noise level of the texel's footprint.
#include "clouds/cloud_sampling.glsl"
#include "clouds/column_map.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, set = 0, binding = 11) buffer CloudCounters { uint viewSamples; uint lightSamples; uint mapSamples; } counters;
layout(set = 0, binding = 13, r32f) uniform writeonly image3D columnImage;

void main() {
  int size = int(cloud.columnMap.z + 0.5);
  int K = int(cloud.columnMap.w + 0.5);
  int j = int(gl_GlobalInvocationID.z);
  // This bake's rows: every w-th from the first (all of them in a full bake); the same rows as the
  // other layers' map's.
  int stride = max(int(cloud.columnAxisU.w + 0.5), 1);
  ivec2 texel = ivec2(gl_GlobalInvocationID.x, int(gl_GlobalInvocationID.y) * stride + int(cloud.columnOrigin.w + 0.5));
  if (texel.x >= size || texel.y >= size || j >= cloud.image.w) return;
  vec2 s = (vec2(texel) + 0.5) / float(size) * 2.0 - 1.0;
  vec2 a = columnMapPlanePoint(s);
  vec3 q = columnMapDirection(a);
  CloudLayer layer = layerAt(j);
  float h = (layer.top_radius - layer.bottom_radius) / float(K);
  vec2 lod = noiseLod(noiseTexels(layer), cloud.aerial.z * max(columnMapTexelSize(a), h));
  int base = j * (K + 1);
  float tau = 0.0;
  imageStore(columnImage, ivec3(texel, base + K), vec4(0.0));
  for (int k = K - 1; k >= 0; --k) {
    tau += layer.extinction * densityAt(layer, q * (layer.bottom_radius + (float(k) + 0.5) * h), lod) * h;
    imageStore(columnImage, ivec3(texel, base + k), vec4(tau));
  }
  atomicAdd(counters.mapSamples, uint(K));
}
