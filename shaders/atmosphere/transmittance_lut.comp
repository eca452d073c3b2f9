#version 450
#extension GL_GOOGLE_include_directive : require
// Transmittance LUT: T(r, mu) = exp(-optical depth to the top of the atmosphere), one texel per
// (r, mu) in Bruneton's parametrization (common/atmosphere_lut.glsl). Ground-hitting rays are
// stored too (the transmittance of the straight line through the planet is never looked up).
#include "atmosphere/atmosphere_block.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D transmittanceLut;
layout(push_constant) uniform Push { int integration_steps; } push;

void main() {
  ivec2 size = imageSize(transmittanceLut);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float r, mu;
  rMuFromTransmittanceUv(atmosphere, (vec2(texel) + 0.5) / vec2(size), size, r, mu);
  vec3 depth = opticalDepthToTop(atmosphere, r, mu, push.integration_steps);
  imageStore(transmittanceLut, texel, vec4(exp(-depth), 1.0));
}
