// atmosphere_sampling.glsl (GPU only): lookups into the precomputed tables. The tables' layouts are
// defined in common/atmosphere_lut.glsl; texture sizes come from textureSize().
#ifndef FIRMAMENT_ATMOSPHERE_SAMPLING_GLSL
#define FIRMAMENT_ATMOSPHERE_SAMPLING_GLSL

#include "atmosphere/atmosphere_block.glsl"

// Transmittance from (r, mu) to the top of the atmosphere.
vec3 transmittanceToTop(sampler2D lut, AtmosphereParameters atmosphere, float r, float mu) {
  ivec2 size = textureSize(lut, 0);
  return textureLod(lut, transmittanceUvFromRMu(atmosphere, r, mu, size), 0.0).rgb;
}

// Transmittance of sunlight arriving at radius r with sun zenith cosine mu_s, including the
// planet's shadow: a sun below the local horizon is faded out over its angular diameter
// (Bruneton 2017, GetTransmittanceToSun), so the terminator has no hard step.
vec3 transmittanceToSun(sampler2D lut, AtmosphereParameters atmosphere, float r, float mu_s) {
  float sin_theta_h = atmosphere.bottom_radius / r;
  float cos_theta_h = -sqrt(max(1.0 - sin_theta_h * sin_theta_h, 0.0));
  float visible = smoothstep(-sin_theta_h * atmosphere.sun_angular_radius,
                             sin_theta_h * atmosphere.sun_angular_radius, mu_s - cos_theta_h);
  return visible * transmittanceToTop(lut, atmosphere, r, mu_s);
}

// Tables of the multiple-scattering field store ln(value) (atmosphere/multiple_scattering_lut.glsl):
// across the Earth's shadow Psi_ms falls by orders of magnitude within a texel or two, and linear
// interpolation of such a fall overestimates it (with 32 x 32 texels it doubled a twilight view's
// multiple scattering at sun zenith 96 deg, docs/atmosphere.md). Bilinear interpolation of the
// logarithm is exact for an exponential fall; where the table is smooth it differs from linear
// interpolation at second order only, and never exceeds it (the bench's noon view unchanged, its
// sunset rows 0.3-0.6 % darker). kLogFloor stands for zero (e^-69 = 1e-30).
const float kLogFloor = -69.0;
vec3 encodeLog(vec3 value) { return log(max(value, vec3(1e-30))); }
vec3 decodeLog(vec3 encoded) { return exp(max(encoded, vec3(kLogFloor))); }

// Hillaire 2020's Psi_ms: radiance per unit scattering coefficient from all orders >= 2, for an
// isotropic phase, at (r, mu_s).
vec3 multipleScattering(sampler2D lut, AtmosphereParameters atmosphere, float r, float mu_s) {
  ivec2 size = textureSize(lut, 0);
  return decodeLog(textureLod(lut, multipleScatteringUv(atmosphere, r, mu_s, size), 0.0).rgb);
}

// The anisotropy table (atmosphere/multiple_scattering_lut.glsl) packs its five RGB coefficients
// c_0..c_4 into kAnisotropyTiles RGBA tiles of the multiple-scattering table's size, side by side
// (width 4 size): the channels in order are c_0.rgb c_1.rgb ... c_4.rgb and one unused. Four bilinear
// fetches of a 2D texture instead of five trilinear ones of a 3D texture (on lavapipe, 16 texel reads
// instead of 40). A table coordinate u stays within its tile's texel centres, so filtering never
// reads a neighbouring tile.
vec2 anisotropyTileUv(vec2 uv, int tile) { return vec2((float(tile) + uv.x) / float(kAnisotropyTiles), uv.y); }
void unpackAnisotropy(vec4 t0, vec4 t1, vec4 t2, vec4 t3, out vec3 c[kAnisotropyTerms]) {
  c[0] = t0.xyz;
  c[1] = vec3(t0.w, t1.xy);
  c[2] = vec3(t1.zw, t2.x);
  c[3] = t2.yzw;
  c[4] = t3.xyz;
}
void packAnisotropy(vec3 c[kAnisotropyTerms], out vec4 t0, out vec4 t1, out vec4 t2, out vec4 t3) {
  t0 = vec4(c[0], c[1].x);
  t1 = vec4(c[1].yz, c[2].xy);
  t2 = vec4(c[2].z, c[3]);
  t3 = vec4(c[4], 0.0);
}

#endif  // FIRMAMENT_ATMOSPHERE_SAMPLING_GLSL
