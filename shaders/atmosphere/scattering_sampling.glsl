// scattering_sampling.glsl (GPU only): lookups into Bruneton 2017's tables, whose parametrizations
// are in common/scattering_lut.glsl, and the transmittance between two points of a ray.
#ifndef FIRMAMENT_SCATTERING_SAMPLING_GLSL
#define FIRMAMENT_SCATTERING_SAMPLING_GLSL

#include "atmosphere/atmosphere_sampling.glsl"
#include "common/scattering_lut.glsl"

// Radius and zenith cosines at distance d along the ray (r, mu), for the view (mu) and the sun
// (mu_s, with nu = cos(view, sun)): the point is r z + d w, so its radius is radiusAfter(r, mu, d),
// and its cosines with the view and the sun are (r mu + d) / r_d and (r mu_s + d nu) / r_d.
void pointAlongRay(float r, float mu, float mu_s, float nu, float d, out float r_d, out float mu_d, out float mu_s_d) {
  r_d = max(radiusAfter(r, mu, d), 1.0);
  mu_d = clampCosine((r * mu + d) / r_d);
  mu_s_d = clampCosine((r * mu_s + d * nu) / r_d);
}

// Transmittance between the ray's start (r, mu) and the point at distance d (Bruneton 2017,
// GetTransmittance). Along one straight line T(x -> top) = T(x -> y) T(y -> top), so
// T(x -> y) = T(r, mu) / T(r_d, mu_d). For a ray that hits the ground, T(r, mu) would cross the
// planet; the reversed ray from y back through x to the top never does: T = T(r_d, -mu_d) / T(r, -mu).
vec3 transmittanceBetween(sampler2D transmittanceLut, AtmosphereParameters atmosphere, float r, float mu, float d,
                          bool hitsGround) {
  float r_d = clamp(radiusAfter(r, mu, d), atmosphere.bottom_radius, atmosphere.top_radius);
  float mu_d = clampCosine((r * mu + d) / r_d);
  vec3 numerator, denominator;
  if (hitsGround) {
    numerator = transmittanceToTop(transmittanceLut, atmosphere, r_d, -mu_d);
    denominator = transmittanceToTop(transmittanceLut, atmosphere, r, -mu);
  } else {
    numerator = transmittanceToTop(transmittanceLut, atmosphere, r, mu);
    denominator = transmittanceToTop(transmittanceLut, atmosphere, r_d, mu_d);
  }
  return min(numerator / max(denominator, vec3(1e-30)), vec3(1.0));
}

// A 4D lookup: two bilinear-in-(mu_s, mu)-and-r fetches from the two nu slices around u_nu,
// blended linearly (the hardware filters three axes; the fourth is folded into x).
vec3 lookupScattering(sampler3D table, ScatteringTableSize size, vec4 uvwz) {
  float slice = uvwz.x * float(size.nu - 1);
  float lower = floor(slice);
  float blend = slice - lower;
  vec3 uvw0 = vec3((lower + uvwz.y) / float(size.nu), uvwz.z, uvwz.w);
  vec3 uvw1 = vec3((min(lower + 1.0, float(size.nu - 1)) + uvwz.y) / float(size.nu), uvwz.z, uvwz.w);
  return mix(textureLod(table, uvw0, 0.0).rgb, textureLod(table, uvw1, 0.0).rgb, blend);
}

// The same lookup, interpolated geometrically along mu_s: L = L0^(1-t) L1^t between the two nearest
// mu_s texels (each still filtered linearly in mu and r, and blended in nu). In twilight the sky's
// radiance falls nearly exponentially with the sun's depression (by e per 0.5-1 deg), about one
// texel per degree there, so linear interpolation would draw a scalloped log-luminance curve whose
// slope jumps at every texel; geometric interpolation follows an exponential exactly, and differs
// from linear by a second-order amount where the light varies slowly (0.1 % for neighbours 10 %
// apart, daytime). Costs twice the fetches of lookupScattering.
vec3 lookupScatteringGeometricMuS(sampler3D table, ScatteringTableSize size, vec4 uvwz) {
  float texelCoordinate = clamp(uvwz.y * float(size.mu_s) - 0.5, 0.0, float(size.mu_s - 1));
  float lower = floor(texelCoordinate);
  float t = texelCoordinate - lower;
  float upper = min(lower + 1.0, float(size.mu_s - 1));
  vec3 l0 = lookupScattering(table, size, vec4(uvwz.x, (lower + 0.5) / float(size.mu_s), uvwz.z, uvwz.w));
  vec3 l1 = lookupScattering(table, size, vec4(uvwz.x, (upper + 0.5) / float(size.mu_s), uvwz.z, uvwz.w));
  const vec3 kTiny = vec3(1e-30);
  return exp(mix(log(max(l0, kTiny)), log(max(l1, kTiny)), t)) * step(kTiny, max(l0, l1));
}

vec3 scatteringAtGeometricMuS(sampler3D table, AtmosphereParameters atmosphere, ScatteringTableSize size, float r,
                              float mu, float mu_s, float nu, bool hitsGround) {
  return lookupScatteringGeometricMuS(table, size, scatteringUvwzFromRMuMuSNu(atmosphere, size, r, mu, mu_s, nu, hitsGround));
}

vec3 scatteringAt(sampler3D table, AtmosphereParameters atmosphere, ScatteringTableSize size, float r, float mu,
                  float mu_s, float nu, bool hitsGround) {
  return lookupScattering(table, size, scatteringUvwzFromRMuMuSNu(atmosphere, size, r, mu, mu_s, nu, hitsGround));
}

// Sunlight reaching a horizontal surface at (r, mu_s): E_sun T_sun max(mu_s, 0), with the planet's
// shadow faded over the sun's disc (transmittanceToSun); the same direct term render_sky.comp uses.
vec3 directIrradiance(sampler2D transmittanceLut, AtmosphereParameters atmosphere, float r, float mu_s) {
  return atmosphere.solar_irradiance * transmittanceToSun(transmittanceLut, atmosphere, r, mu_s) * max(mu_s, 0.0);
}

#endif  // FIRMAMENT_SCATTERING_SAMPLING_GLSL
