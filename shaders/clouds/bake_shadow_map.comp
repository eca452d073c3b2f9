#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the Beer shadow map (common/cloud_shadow.glsl): per texel, the sun ray through all cloud
// layers marched in `steps` equal steps (midpoint samples of the full density), giving the front
// depth d_f, the mean extinction over [d_f, d_b] and the total optical depth. Texels with no cloud
// store (march length, 0, 0): no optical depth at any depth.
#include "clouds/cloud_sampling.glsl"
#include "common/cloud_shadow.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 13, rgba32f) uniform writeonly image2D shadowImage;

void main() {
  int size = cloud.shadowSize.x;
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(size)))) return;
  vec3 sun = cloud.sun_direction.xyz;
  float extent = cloud.shadowCentre.w;
  float start = cloud.shadowAxisU.w;
  float marchLength = cloud.shadowAxisV.w;
  int steps = max(cloud.shadowSize.y, 1);
  vec2 ab = (vec2(texel) + 0.5) / float(size) - 0.5;
  vec3 entry = cloud.shadowCentre.xyz + ab.x * extent * cloud.shadowAxisU.xyz + ab.y * extent * cloud.shadowAxisV.xyz + start * sun;
  float h = marchLength / float(steps);
  float front = marchLength, back = 0.0, tau = 0.0;
  for (int i = 0; i < steps; ++i) {
    float depth = (float(i) + 0.5) * h;
    vec3 p = entry - sun * depth;
    float sigma = 0.0;
    for (int l = 0; l < cloud.image.w; ++l) {
      CloudLayer layer = layerAt(l);
      sigma += layer.extinction * densityAt(layer, p, vec2(0.0));
    }
    if (sigma > 0.0) {
      front = min(front, depth - 0.5 * h);
      back = depth + 0.5 * h;
      tau += sigma * h;
    }
  }
  vec4 value = tau > 0.0 ? vec4(front, tau / max(back - front, h), tau, 0.0) : vec4(marchLength, 0.0, 0.0, 0.0);
  imageStore(shadowImage, texel, value);
}
