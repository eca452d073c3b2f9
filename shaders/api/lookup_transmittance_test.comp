#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: evaluates firmament/atmosphere_lookup.glsl's firmamentTransmittanceToTop, the function a
// host's shader calls, over the transmittance table Firmament exports (Sky::lookups()), for
// tests/api/test_lookup_transmittance.cpp, which compares it with the atmosphere's own integral in
// double on the CPU. One (r, mu) per input, one rgb transmittance per output.
#include "firmament/atmosphere_lookup.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D transmittanceLut;
layout(std430, set = 0, binding = 1) readonly buffer Inputs { vec2 inputs[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Outputs { vec4 outputs[]; };
layout(push_constant) uniform Push {
  vec4 radii;
  uint count;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  FirmamentAtmosphere a;
  a.radii = push.radii;
  a.sun = vec4(0.0, 0.0, 1.0, 0.0);
  a.sunIlluminance = vec4(0.0);
  a.image = vec4(0.0);
  outputs[i] = vec4(firmamentTransmittanceToTop(transmittanceLut, a, inputs[i].x, inputs[i].y), 0.0);
}
