#version 450
#extension GL_GOOGLE_include_directive : require
// Bruneton 2017's precomputation, step 1: the sun's direct irradiance on a horizontal surface,
// E_0(r, mu_s) = E_sun T_sun(r, mu_s) max(mu_s, 0) (W m^-2 nm^-1), into the "delta" irradiance table
// that lights the ground for the second scattering order. The ground irradiance table itself holds
// the sky's (indirect) irradiance only, so it starts at zero here: the direct part is evaluated
// exactly at render time from the transmittance table instead.
#include "atmosphere/scattering_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D deltaIrradiance;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D irradiance;

void main() {
  ivec2 size = imageSize(deltaIrradiance);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float r, mu_s;
  rMuSFromIrradianceUv(atmosphere, (vec2(texel) + 0.5) / vec2(size), size, r, mu_s);
  imageStore(deltaIrradiance, texel, vec4(directIrradiance(transmittanceLut, atmosphere, r, mu_s), 0.0));
  imageStore(irradiance, texel, vec4(0.0));
}
