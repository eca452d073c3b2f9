#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: evaluates common/moon_disc.glsl and common/night_sky.glsl in float for
// tests/gpu/test_night_functions.cpp, which runs the same headers in double on the CPU.
// Input per sample: a = (direction x, y, z, wavelength nm), b = (cos zenith, phase angle, C, earthshine):
// the disc's per-frame constants come from the CPU in double (astro::moonLight), as in the renderer.
// Output per sample: moon disc radiance, airglow, zodiacal factor, stellar background factor.
#include "common/moon_disc.glsl"
#include "common/night_sky.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Outputs { float outputs[]; };
layout(push_constant) uniform Push {
  float angularRadius;
  float observerRadius;
  float planetRadius;
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  vec4 a = inputs[2u * i];
  vec4 b = inputs[2u * i + 1u];
  vec3 direction = vec3(a.x, a.y, a.z);
  float alpha = b.y;
  vec3 moonDir = vec3(0.0, 0.0, 1.0);
  vec3 sunFromMoon = vec3(sin(alpha), 0.0, -cos(alpha));
  float scale = b.z;
  float earthshine = b.w;
  uint o = 4u * i;
  outputs[o + 0u] = moonDiscRadiance(direction, moonDir, sunFromMoon, push.angularRadius, scale, earthshine, 1.0);
  outputs[o + 1u] = airglowSpectralRadiance(a.w, 10.0, b.x, push.observerRadius, push.planetRadius, 1.0);
  outputs[o + 2u] = zodiacalSolarSpectrumFactor(direction);
  outputs[o + 3u] = stellarBackgroundSolarSpectrumFactor(direction.z);
}
