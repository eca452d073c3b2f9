#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the other layers' map (clouds/other_layer_map.glsl): per texel, the line along the sun through
// its plane point, and per layer the optical depth of that line's sunward crossing, in lightSteps x
// otherLayerLightStepsScale equal steps per layer thickness of the crossing (2 to 4 times that, as the
// march's crossings had: cloud_sampling.glsl opticalDepthThroughOtherLayers), midpoint samples of the
// full density at the noise level of the texel's footprint.
#include "clouds/cloud_sampling.glsl"
#include "clouds/other_layer_map.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, set = 0, binding = 11) buffer CloudCounters { uint viewSamples; uint lightSamples; uint mapSamples; } counters;
layout(set = 0, binding = 13, rgba32f) uniform writeonly image2D otherLayerImage;

void main() {
  int size = int(cloud.otherLayerMap.z + 0.5);
  int tiles = int(cloud.otherLayerMap.w + 0.5);
  // This bake's rows: every w-th from the first (all of them in a full bake).
  int stride = max(int(cloud.otherLayerAxisU.w + 0.5), 1);
  ivec2 texel = ivec2(gl_GlobalInvocationID.x, int(gl_GlobalInvocationID.y) * stride + int(cloud.otherLayerOrigin.w + 0.5));
  if (texel.x >= size || texel.y >= size * tiles) return;
  int tile = texel.y / size;
  vec2 s = (vec2(texel.x, texel.y - tile * size) + 0.5) / float(size) * 2.0 - 1.0;
  vec2 a = otherLayerMapPlanePoint(s);
  vec3 sun = cloud.otherLayerSun.xyz;
  vec3 o = cloud.otherLayerOrigin.xyz + a.x * cloud.otherLayerAxisU.xyz + a.y * cloud.otherLayerAxisV.xyz;
  // The line's periapsis b and its radius.
  vec3 b = o - sun * dot(o, sun);
  float rc = length(b);
  int lightSteps = max(cloud.steps.y, 1);
  int crossingSteps = max(int(float(lightSteps) * cloud.weatherPlanet.w + 0.5), 1);
  float footprint = cloud.aerial.z * otherLayerMapTexelSize(a);
  vec4 tau = vec4(0.0);
  uint samples = 0u;  // the maps' samples (CloudSampleCounts::mapPerPixel)
  for (int c = 0; c < 4; ++c) {
    int j = 4 * tile + c;
    if (j >= cloud.image.w) break;
    CloudLayer layer = layerAt(j);
    vec2 crossing = otherLayerMapCrossing(rc, layer.bottom_radius, layer.top_radius);
    float length_m = crossing.y - crossing.x;
    if (!(length_m > 0.0)) continue;
    float thickness = layer.top_radius - layer.bottom_radius;
    int n = lightStepsForLength(crossingSteps, length_m, thickness, 2);
    float h = length_m / float(n);
    vec2 lod = noiseLod(noiseTexels(layer), footprint);
    float sum = 0.0;
    for (int k = 0; k < n; ++k) sum += densityAt(layer, b + sun * (crossing.x + (float(k) + 0.5) * h), lod);
    tau[c] = layer.extinction * h * sum;
    samples += uint(n);
  }
  if (samples > 0u) atomicAdd(counters.mapSamples, samples);
  imageStore(otherLayerImage, texel, tau);
}
