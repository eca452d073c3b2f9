// air_integrand.glsl (GPU only): the clear-sky in-scattering integrand at one point of a view ray,
// and the energy-conserving integration of one step of it. One source for every march of the air:
// the per-pixel sky and the sky-view table (sky/sky_march.glsl), the aerial-perspective volume
// (sky/aerial_perspective_volume.comp) and the clouds' per-pixel air march (clouds/render_clouds.glsl):
//   dL = T(0,t) [ sigma_s^R(t) (p_R(nu) E_sun T_sun(t) + Psi_R(t)) + sigma_s^M(t) Psi_M(t) ]        (sky-like)
//      + T(0,t) sigma_s^M(t) p_M(nu) E_sun T_sun(t)                                               (sun-like)
// with T_sun from the transmittance table times the planet's shadow, and Psi the multiply scattered
// light scattered into the view by each constituent (Psi_ms plus its anisotropy).
#ifndef FIRMAMENT_AIR_INTEGRAND_GLSL
#define FIRMAMENT_AIR_INTEGRAND_GLSL

#include "atmosphere/atmosphere_sampling.glsl"

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

// The integrand at p (planet-centred, m) for a view along `dir`: the sources per unit length with the
// sky's and with the sun's spectrum, and the extinction. phase_r, phase_m: the Rayleigh and aerosol
// phase functions at nu = dot(dir, sun) (constant along a ray, so computed once per ray).
struct AirSample {
  vec3 sky_source;
  vec3 sunlike_source;
  vec3 extinction;
  vec3 sky_single_source;  // the part of sky_source that is single scattering of sunlight (Rayleigh)
};
AirSample airSampleAt(AtmosphereParameters atmosphere, sampler2D transmittance_lut, sampler2D multiple_scattering_lut,
                      sampler2D anisotropy_lut, vec3 p, vec3 sun, vec3 dir, float phase_r, float phase_m) {
  float r_p = length(p);
  float mu_s_p = dot(p, sun) / r_p;
  vec3 rayleigh = rayleighScatteringAt(atmosphere, r_p);
  vec3 mie = mieScatteringAt(atmosphere, r_p);
  vec3 sun_light = transmittanceToSun(transmittance_lut, atmosphere, r_p, mu_s_p) * atmosphere.solar_irradiance;
  MultipleScatteringSource ms = multipleScatteringInto(atmosphere, multiple_scattering_lut, anisotropy_lut, p, r_p,
                                                       mu_s_p, sun, dir);
  AirSample s;
  s.sky_single_source = rayleigh * phase_r * sun_light;
  s.sky_source = s.sky_single_source + rayleigh * ms.rayleigh + mie * ms.mie;
  s.sunlike_source = mie * phase_m * sun_light;
  s.extinction = extinctionAt(atmosphere, r_p);
  return s;
}

// One step of length dt through extinction sigma held constant: its transmittance e^(-sigma dt) and
// the integral of the transmittance over it (stepIntegral), the weights of every source on that step.
struct AirStepWeights {
  vec3 transmittance;
  vec3 integral;
};
AirStepWeights airStepWeights(vec3 extinction, float dt) {
  AirStepWeights w;
  w.transmittance = exp(-extinction * dt);
  w.integral = stepIntegral(extinction, dt, w.transmittance);
  return w;
}

// One step with the sample's coefficients held constant (Hillaire 2016): adds the step's light,
// attenuated by the throughput so far, and multiplies the throughput by the step's transmittance.
void accumulateAirStep(AirSample s, AirStepWeights w, inout vec3 sky, inout vec3 sunlike, inout vec3 throughput) {
  sky += throughput * s.sky_source * w.integral;
  sunlike += throughput * s.sunlike_source * w.integral;
  throughput *= w.transmittance;
}
void accumulateAirStep(AirSample s, float dt, inout vec3 sky, inout vec3 sunlike, inout vec3 throughput) {
  accumulateAirStep(s, airStepWeights(s.extinction, dt), sky, sunlike, throughput);
}

#endif  // FIRMAMENT_AIR_INTEGRAND_GLSL
