// sky_march.glsl (GPU only): the clear-sky integral along one view ray, shared by the per-pixel
// render and the sky-view LUT so both compute exactly the same thing:
//   L = ∫_0^D T(0,t) [ sigma_s^R(t) p_R(nu) + sigma_s^M(t) p_M(nu) ] E_sun T_sun(t)
//                  + [ sigma_s^R(t) + sigma_s^M(t) ] Psi_ms(t)  dt
//     + T(0,D) L_ground                  (if the ray meets the ground: sun and sky irradiance)
// Each step is integrated analytically for constant coefficients (Hillaire 2016's energy-conserving
// form), and samples are spaced quadratically to resolve the dense air near the camera.
#ifndef FIRMAMENT_SKY_MARCH_GLSL
#define FIRMAMENT_SKY_MARCH_GLSL

#include "atmosphere/atmosphere_sampling.glsl"
#include "atmosphere/irradiance_sampling.glsl"

struct SkyMarch {
  vec3 rgb;          // in-scattered light plus the lit ground, linear Rec.709 cd/m² (no sun disc)
  vec3 throughput;   // transmittance from the camera to where the ray leaves the atmosphere
  bool hits_ground;
};

// ∫_0^dt e^(-sigma_t x) dx = (1 - e^(-k)) / sigma_t with k = sigma_t dt, written as dt (1 - e^-k)/k and
// replaced by dt for k -> 0 so it stays exact for thin media.
vec3 stepIntegral(vec3 extinction, float dt, vec3 step_transmittance) {
  vec3 k = extinction * dt;
  return mix(dt * (1.0 - step_transmittance) / max(k, vec3(1e-12)), vec3(dt), lessThan(k, vec3(1e-4)));
}

// The multiply scattered light at p scattered into the view direction `dir` by Rayleigh (.rayleigh) and
// aerosol (.mie) scattering, per unit scattering coefficient: the isotropic part Psi_ms plus the
// anisotropy table's harmonics weighted by the phases' Legendre moments (Funk-Hecke; see
// atmosphere/multiple_scattering_lut.glsl). Zero anisotropy (Hillaire's form) leaves Psi_ms.
struct MultipleScatteringSource {
  vec3 rayleigh;
  vec3 mie;
};
MultipleScatteringSource multipleScatteringInto(AtmosphereParameters atmosphere, sampler2D multiple_scattering_lut,
                                                sampler2D anisotropy_lut, vec3 p, float r_p, float mu_s_p, vec3 sun,
                                                vec3 dir) {
  vec3 up = p / r_p;
  vec3 sun_h = sun - mu_s_p * up;
  float sun_h_length = length(sun_h);
  // With the sun at the zenith the field is symmetric about the vertical: any horizontal y will do.
  vec3 y = sun_h_length > 1e-6 ? sun_h / sun_h_length : normalize(cross(up, abs(up.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  vec3 w = vec3(dot(dir, cross(y, up)), dot(dir, y), dot(dir, up));
  ivec2 size = textureSize(multiple_scattering_lut, 0);
  vec2 uv = multipleScatteringUv(atmosphere, r_p, mu_s_p, size);
  vec3 psi = decodeLog(textureLod(multiple_scattering_lut, uv, 0.0).rgb);
  vec3 c[kAnisotropyTerms];  // c_lm / Psi_ms
  unpackAnisotropy(textureLod(anisotropy_lut, anisotropyTileUv(uv, 0), 0.0), textureLod(anisotropy_lut, anisotropyTileUv(uv, 1), 0.0),
                   textureLod(anisotropy_lut, anisotropyTileUv(uv, 2), 0.0), textureLod(anisotropy_lut, anisotropyTileUv(uv, 3), 0.0), c);
  vec3 l1 = psi * (c[0] * anisotropyHarmonic(0, w) + c[1] * anisotropyHarmonic(1, w));
  vec3 l2 = psi * (c[2] * anisotropyHarmonic(2, w) + c[3] * anisotropyHarmonic(3, w) + c[4] * anisotropyHarmonic(4, w));
  vec2 mie_moments = miePhaseMoments();
  MultipleScatteringSource s;
  s.rayleigh = max(psi + kRayleighPhaseMoment2 * l2, vec3(0.0));
  s.mie = max(psi + mie_moments.x * l1 + mie_moments.y * l2, vec3(0.0));
  return s;
}

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
    float r_p = length(p);
    float mu_s_p = dot(p, sun) / r_p;
    vec3 rayleigh = rayleighScatteringAt(atmosphere, r_p);
    vec3 mie = mieScatteringAt(atmosphere, r_p);
    vec3 extinction = extinctionAt(atmosphere, r_p);
    vec3 sun_light = transmittanceToSun(transmittance_lut, atmosphere, r_p, mu_s_p) * atmosphere.solar_irradiance;
    MultipleScatteringSource ms = multipleScatteringInto(atmosphere, multiple_scattering_lut, anisotropy_lut, p, r_p,
                                                         mu_s_p, sun, dir);
    vec3 sky_source = rayleigh * (phase_r * sun_light + ms.rayleigh) + mie * ms.mie;
    vec3 sunlike_source = mie * phase_m * sun_light;
    vec3 step_transmittance = exp(-extinction * dt);
    vec3 integral = stepIntegral(extinction, dt, step_transmittance);
    sky += result.throughput * sky_source * integral;
    sunlike += result.throughput * sunlike_source * integral;
    result.throughput *= step_transmittance;
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
