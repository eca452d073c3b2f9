#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: evaluates the shared atmosphere headers (common/atmosphere_medium.glsl,
// common/atmosphere_lut.glsl) in float for tests/atmosphere/test_atmosphere_shared_functions.cpp,
// which runs the same headers in double on the CPU. One row of 16 floats per input (r, mu, mu_s, nu).
#include "atmosphere/atmosphere_block.glsl"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 1) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Outputs { float outputs[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float r = inputs[i].x, mu = inputs[i].y, mu_s = inputs[i].z, nu = inputs[i].w;
  vec3 extinction = extinctionAt(atmosphere, r);
  vec3 depth = opticalDepthToTop(atmosphere, r, mu, 64);
  vec2 uv = transmittanceUvFromRMu(atmosphere, r, mu, ivec2(256, 64));
  float r_back, mu_back;
  rMuFromTransmittanceUv(atmosphere, uv, ivec2(256, 64), r_back, mu_back);
  vec2 ms_uv = multipleScatteringUv(atmosphere, r, mu_s, ivec2(32, 32));
  uint o = 16u * i;
  outputs[o + 0u] = extinction.x;
  outputs[o + 1u] = extinction.y;
  outputs[o + 2u] = extinction.z;
  outputs[o + 3u] = rayleighPhase(nu);
  outputs[o + 4u] = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
  outputs[o + 5u] = depth.x;
  outputs[o + 6u] = depth.y;
  outputs[o + 7u] = depth.z;
  outputs[o + 8u] = uv.x;
  outputs[o + 9u] = uv.y;
  outputs[o + 10u] = r_back;
  outputs[o + 11u] = mu_back;
  outputs[o + 12u] = ms_uv.x;
  outputs[o + 13u] = ms_uv.y;
  outputs[o + 14u] = sunLimbDarkening(nu, atmosphere.sun_angular_radius);
  outputs[o + 15u] = henyeyGreensteinPhase(0.7, nu);
}
