// sky_march.glsl (GPU only): the clear-sky integral along one view ray, shared by the per-pixel
// render and the sky-view LUT so both compute exactly the same thing:
//   L = ∫_0^D T(0,t) [ sigma_s^R(t) p_R(nu) + sigma_s^M(t) p_M(nu) ] E_sun T_sun(t)
//                  + [ sigma_s^R(t) + sigma_s^M(t) ] Psi_ms(t)  dt
//     + T(0,D) L_ground                  (if the ray meets the ground: sun and sky irradiance)
// Each step is integrated analytically for constant coefficients (Hillaire 2016's energy-conserving
// form), and samples are spaced quadratically to resolve the dense air near the camera. The integrand
// and the step are atmosphere/air_integrand.glsl's, shared with the aerial-perspective volume.
#ifndef FIRMAMENT_SKY_MARCH_GLSL
#define FIRMAMENT_SKY_MARCH_GLSL

#include "atmosphere/air_integrand.glsl"
#include "atmosphere/atmosphere_sampling.glsl"
#include "atmosphere/irradiance_sampling.glsl"

struct SkyMarch {
  vec3 rgb;          // in-scattered light plus the lit ground, linear Rec.709 cd/m² (no sun disc)
  vec3 throughput;   // transmittance from the camera to where the ray leaves the atmosphere
  bool hits_ground;
};

// origin: planet-centred (m); dir, sun: unit vectors in the same frame.
// sky_irradiance_lut: E_sky(r, mu_s) on a horizontal surface (atmosphere/fms_sky_irradiance.comp).
SkyMarch marchSky(AtmosphereParameters atmosphere, sampler2D transmittance_lut, sampler2D multiple_scattering_lut,
                  sampler2D anisotropy_lut, sampler2D sky_irradiance_lut, vec3 origin, vec3 dir, vec3 sun, int steps) {
  SkyMarch result;
  result.rgb = vec3(0.0);
  result.throughput = vec3(1.0);
  result.hits_ground = false;
  float r = length(origin);
  float mu = dot(origin, dir) / r;
  if (r > atmosphere.top_radius) {
    // From space: jump to where the ray enters the atmosphere, if it does.
    if (!rayIntersectsGround(r, mu, atmosphere.top_radius)) return result;
    origin += dir * distanceToBottomAtmosphereBoundary(r, mu, atmosphere.top_radius);
    r = atmosphere.top_radius;
    mu = dot(origin, dir) / length(origin);
  }
  // A camera below the ground sphere sees from the ground (there is nothing to render below it).
  r = max(r, atmosphere.bottom_radius + 0.01);
  vec3 start = normalize(origin) * r;
  float nu = dot(dir, sun);
  // Light with a solar spectrum (aerosol single scattering, nearly grey for Angstrom alpha near 0,
  // and the ground's reflection of sunlight) is converted with the sun's factors; Rayleigh and
  // multiple scattering with the sky's (see atmosphere/atmosphere_spectra.h).
  vec3 sky = vec3(0.0);
  vec3 sunlike = vec3(0.0);
  result.hits_ground = rayIntersectsGround(atmosphere, r, mu);
  float path_length = distanceToNearestAtmosphereBoundary(atmosphere, r, mu);
  steps = max(steps, 1);
  float phase_r = rayleighPhase(nu);
  float phase_m = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
  float t_previous = 0.0;
  for (int i = 1; i <= steps; ++i) {
    // quadratic spacing t_i = D (i/N)^2; the step's coefficients are taken at its midpoint
    float f = float(i) / float(steps);
    float t_next = path_length * f * f;
    float dt = t_next - t_previous;
    vec3 p = start + dir * (0.5 * (t_previous + t_next));
    t_previous = t_next;
    AirSample air = airSampleAt(atmosphere, transmittance_lut, multiple_scattering_lut, anisotropy_lut, p, sun, dir,
                                phase_r, phase_m);
    accumulateAirStep(air, dt, sky, sunlike, result.throughput);
  }
  if (result.hits_ground) {
    // Lambertian ground: albedo / pi * (E_sun T_sun max(mu_s, 0) + E_sky).
    vec3 p = start + dir * path_length;
    float r_g = length(p);
    float mu_s_g = dot(p, sun) / r_g;
    vec3 sun_light = transmittanceToSun(transmittance_lut, atmosphere, r_g, mu_s_g) * atmosphere.solar_irradiance;
    sunlike += result.throughput * atmosphere.ground_albedo / kPi * sun_light * max(mu_s_g, 0.0);
    // Skylight reflected by the ground has the sky's spectrum: converted with the sky's factors.
    sky += result.throughput * atmosphere.ground_albedo / kPi * irradianceLookup(sky_irradiance_lut, atmosphere, r_g, mu_s_g);
  }
  result.rgb = skyRadianceToRgb() * sky + sunRadianceToRgb() * sunlike;
  return result;
}

#endif  // FIRMAMENT_SKY_MARCH_GLSL
