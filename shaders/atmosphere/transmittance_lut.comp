#version 450
#extension GL_GOOGLE_include_directive : require
// Transmittance LUT: T(r, mu) = exp(-optical depth to the top of the atmosphere), one texel per
// (r, mu) in Bruneton's parametrization (common/atmosphere_lut.glsl). Ground-hitting rays are
// stored too (the transmittance of the straight line through the planet is never looked up).
#include "atmosphere/atmosphere_block.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D transmittanceLut;
// The radiance of the sun disc's centre seen through the atmosphere from (r, mu), in linear Rec.709
// cd/m²: sum over spectral batches of M_sun (T ⊙ E_sun I(1)/E). The render multiplies it by the limb
// darkening, so the sun's colour needs no per-pixel loop over batches.
layout(set = 0, binding = 2, rgba32f) uniform image2D sunRadianceLut;
layout(push_constant) uniform Push { int integration_steps; int accumulate; } push;

void main() {
  ivec2 size = imageSize(transmittanceLut);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float r, mu;
  rMuFromTransmittanceUv(atmosphere, (vec2(texel) + 0.5) / vec2(size), size, r, mu);
  vec3 depth = opticalDepthToTop(atmosphere, r, mu, push.integration_steps);
  vec3 transmittance = exp(-depth);
  imageStore(transmittanceLut, texel, vec4(transmittance, 1.0));
  vec3 sun = sunRadianceToRgb() * (transmittance * atmosphere.solar_irradiance) *
             sunDiscCentreFactor(atmosphere.sun_angular_radius);
  if (push.accumulate != 0) sun += imageLoad(sunRadianceLut, texel).rgb;
  imageStore(sunRadianceLut, texel, vec4(sun, 1.0));
}
