#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the deep shadow map (clouds/deep_shadow_map.glsl): per texel, the line along the sun through its
// plane point, and per layer the optical depth from each of its K + 1 levels up to the layer top along
// that line, one midpoint sample of the full density per level segment (up to 4 where a segment is
// longer than two level spacings: a low sun), each at the noise level the march's own light samples read
// at that distance from the camera.
#include "common/cloud_march.glsl"
#include "clouds/cloud_sampling.glsl"
#include "clouds/deep_shadow_map.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, set = 0, binding = 11) buffer CloudCounters { uint viewSamples; uint lightSamples; uint mapSamples; } counters;
layout(set = 0, binding = 13, r32f) uniform writeonly image3D deepShadowImage;

void main() {
  int size = int(cloud.deepShadowMap.x + 0.5);
  int K = int(cloud.deepShadowMap.y + 0.5);
  int j = int(gl_GlobalInvocationID.z);
  // This bake's rows: every w-th from the first (all of them in a full bake); the other layers' map's.
  int stride = max(int(cloud.otherLayerAxisU.w + 0.5), 1);
  ivec2 texel = ivec2(gl_GlobalInvocationID.x, int(gl_GlobalInvocationID.y) * stride + int(cloud.otherLayerOrigin.w + 0.5));
  if (texel.x >= size || texel.y >= size || j >= cloud.image.w) return;
  vec2 s = (vec2(texel) + 0.5) / float(size) * 2.0 - 1.0;
  vec2 a = otherLayerMapPlanePoint(s);
  vec3 sun = cloud.otherLayerSun.xyz;
  vec3 o = cloud.otherLayerOrigin.xyz + a.x * cloud.otherLayerAxisU.xyz + a.y * cloud.otherLayerAxisV.xyz;
  // The line's periapsis b and its radius r_c; level r lies t(r) from b (sunLineDistanceToRadius; 0
  // below r_c: levels the line never reaches repeat its lowest point).
  vec3 b = o - sun * dot(o, sun);
  float rc = length(b);
  CloudLayer layer = layerAt(j);
  float h = (layer.top_radius - layer.bottom_radius) / float(K);
  vec2 texels = noiseTexels(layer);
  int base = j * (K + 1);
  float tau = 0.0;
  uint samples = 0u;
  imageStore(deepShadowImage, ivec3(texel, base + K), vec4(0.0));
  float rUpper = layer.top_radius;
  float tUpper = sunLineDistanceToRadius(rc, rUpper);
  for (int k = K - 1; k >= 0; --k) {
    float rLower = layer.bottom_radius + float(k) * h;
    float tLower = sunLineDistanceToRadius(rc, rLower);
    float segment = tUpper - tLower;
    int S = clamp(int(ceil(segment / (2.0 * h))), 1, 4);
    float sub = segment / float(S);
    float sum = 0.0;
    for (int i = 0; i < S; ++i) {
      vec3 x = b + sun * (tLower + (float(i) + 0.5) * sub);
      // The noise level the march's own light samples would read there: its view step's at that
      // distance from the camera (common/cloud_march.glsl).
      float step = cloudViewStep(length(x - cloud.otherLayerOrigin.xyz), cloud.stepGrowth.x, max(cloud.stepGrowth.y, 1.0), cloud.stepGrowth.z);
      sum += densityAt(layer, x, noiseLod(texels, cloud.aerial.z * step));
    }
    tau += layer.extinction * sum * sub;
    samples += uint(S);
    imageStore(deepShadowImage, ivec3(texel, base + k), vec4(tau));
    tUpper = tLower;
  }
  atomicAdd(counters.mapSamples, samples);
}
