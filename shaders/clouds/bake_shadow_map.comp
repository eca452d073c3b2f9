#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the Beer shadow map (common/cloud_shadow.glsl): per texel, the sun ray through all cloud
// layers marched in `steps` equal steps over its stretch inside the layers' shells (midpoint samples of the full
// density), giving the front depth d_f, the mean extinction over [d_f, d_b] and the total optical depth. Texels with no
// cloud store (march length, 0, 0): no optical depth at any depth.
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
  vec3 entry = cloud.shadowCentre.xyz + ab.x * extent * cloud.shadowAxisU.xyz + ab.y * extent * cloud.shadowAxisV.xyz +
               start * sun;
  // The steps span the ray's stretch inside the layers' outer shell (from the highest top down to the
  // lowest base), not the whole march: texels far from the centre along the sun's azimuth meet the
  // layers kilometres deeper or shallower than the centre's (the map's start distance L allows for it).
  float inner = 1.0e30, outer = 0.0;
  for (int l = 0; l < cloud.image.w; ++l) {
    CloudLayer layer = layerAt(l);
    inner = min(inner, layer.bottom_radius);
    outer = max(outer, layer.top_radius);
  }
  float r = length(entry);
  float mu = dot(entry, -sun) / r;
  vec2 first, second;
  cloudShellSegments(r, mu, inner, outer, marchLength, first, second);
  float t0 = first.x, t1 = max(first.y, first.x);
  float h = max(t1 - t0, 0.0) / float(steps);
  float front = marchLength, back = 0.0, tau = 0.0;
  for (int i = 0; i < steps && h > 0.0; ++i) {
    float depth = t0 + (float(i) + 0.5) * h;
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
