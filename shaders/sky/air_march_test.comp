#version 450
#extension GL_GOOGLE_include_directive : require
// Test only (tests/sky/test_aerial_perspective.cpp): the air along given rays by a fine march of
// equal steps of the clear-sky integrand (atmosphere/air_integrand.glsl), with the conventions of the
// aerial-perspective volume (sky/aerial_perspective_volume.comp): only the stretch inside the top of
// the atmosphere counts, samples below the ground take the air at the ground below them, and the
// aerosols' single scattering is returned without its phase function. Per ray: the sky-like light
// and the aerosols' light (linear Rec.709 cd/m^2, the block's wavelengths) and the transmittance.
#include "atmosphere/air_integrand.glsl"
#include "common/geometry.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3) uniform sampler2D multipleScatteringAnisotropy;
layout(std430, set = 0, binding = 4) readonly buffer Rays { vec4 rays[]; };       // per ray: origin, depth; direction, steps
layout(std430, set = 0, binding = 5) writeonly buffer Results { vec4 results[]; }; // per ray: sky-like, aerosol, transmittance
layout(push_constant) uniform Push {
  vec4 sun;  // xyz
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  vec3 origin = rays[2 * i].xyz;
  float depth = rays[2 * i].w;
  vec3 dir = rays[2 * i + 1].xyz;
  int steps = max(int(rays[2 * i + 1].w), 1);
  vec3 sun = push.sun.xyz;
  float r = length(origin);
  float mu = clamp(dot(origin, dir) / r, -1.0, 1.0);
  float t_in = 0.0, t_out = 0.0, near_root, far_root;
  if (raySphereRoots(r, mu, atmosphere.top_radius, near_root, far_root) && far_root > 0.0) {
    t_in = max(near_root, 0.0);
    t_out = far_root;
  }
  float a = clamp(0.0, t_in, t_out);
  float b = clamp(depth, t_in, t_out);
  float dt = max(b - a, 0.0) / float(steps);
  float phase_r = rayleighPhase(dot(dir, sun));
  vec3 sky = vec3(0.0), sunlike = vec3(0.0), throughput = vec3(1.0);
  for (int s = 0; s < steps; ++s) {
    vec3 p = origin + dir * (a + (float(s) + 0.5) * dt);
    float r_p = length(p);
    p *= max(r_p, atmosphere.bottom_radius) / r_p;
    AirSample air = airSampleAt(atmosphere, transmittanceLut, multipleScatteringLut, multipleScatteringAnisotropy, p, sun, dir,
                                phase_r, 1.0);
    accumulateAirStep(air, dt, sky, sunlike, throughput);
  }
  results[3 * i] = vec4(skyRadianceToRgb() * sky, 1.0);
  results[3 * i + 1] = vec4(sunRadianceToRgb() * sunlike, 1.0);
  results[3 * i + 2] = vec4(throughput, 1.0);
}
