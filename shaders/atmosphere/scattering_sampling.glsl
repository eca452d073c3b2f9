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
