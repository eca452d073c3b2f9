#version 450
#extension GL_GOOGLE_include_directive : require
// Sky-view LUT (Hillaire 2020, section 5.3): the sky as seen from the camera's altitude for the
// current sun, in (azimuth from the sun, zenith angle), computed per frame with the same march as the
// per-pixel path (sky/sky_march.glsl), already converted to linear Rec.709 cd/m² and summed over the
// spectral batches. The render then reads one texel per pixel instead of marching.
#include "sky/sky_march.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3, rgba32f) uniform image2D skyViewLut;
layout(set = 0, binding = 4) uniform sampler2D skyIrradianceLut;
layout(set = 0, binding = 5) uniform sampler2D multipleScatteringAnisotropy;
layout(push_constant) uniform Push {
  float camera_radius;  // m from the planet centre (inside the atmosphere)
  float mu_s;           // cosine of the sun zenith angle at the camera
  int steps;
  int accumulate;       // add to the texel (spectral batches after the first)
} push;

void main() {
  ivec2 size = imageSize(skyViewLut);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float theta, cos_phi;
  anglesFromSkyViewUv(atmosphere, push.camera_radius, (vec2(texel) + 0.5) / vec2(size), theta, cos_phi);
  float sin_phi = sqrt(max(1.0 - cos_phi * cos_phi, 0.0));
  // Local frame: camera on +z, sun in the x-z plane, phi measured from the sun's azimuth.
  vec3 origin = vec3(0.0, 0.0, push.camera_radius);
  vec3 sun = vec3(sqrt(max(1.0 - push.mu_s * push.mu_s, 0.0)), 0.0, push.mu_s);
  vec3 dir = vec3(sin(theta) * cos_phi, sin(theta) * sin_phi, cos(theta));
  SkyMarch m = marchSky(atmosphere, transmittanceLut, multipleScatteringLut, multipleScatteringAnisotropy, skyIrradianceLut, origin, dir, sun, push.steps);
  vec3 rgb = m.rgb;
  if (push.accumulate != 0) rgb += imageLoad(skyViewLut, texel).rgb;
  imageStore(skyViewLut, texel, vec4(rgb, 1.0));
}
