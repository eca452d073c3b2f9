#version 450
#extension GL_GOOGLE_include_directive : require
// Ground irradiance table for the f_ms path (Hillaire 2020): the sky's irradiance on a horizontal
// surface at (r, mu_s),
//   E_sky(r, mu_s) = ∫_upper hemisphere L(r, w_i) cos(theta_i) dw_i                 (W m^-2 nm^-1),
// where L is the radiance that render_sky.comp itself would show along w_i: single scattering with
// the Rayleigh and Cornette-Shanks phases plus (sigma_s^R + sigma_s^M) Psi_ms for all higher orders,
// integrated along the ray with the same energy-conserving step (Hillaire 2016) and quadratic spacing.
// The table therefore lights the ground with exactly the sky the f_ms path draws, at the cost of a
// 64 x 16 table (about 1/20 of the transmittance table's work), instead of requiring the 4D tables.
// Directions: a midpoint grid of theta_samples (theta in [0, pi/2]) x 2 theta_samples (phi) cells.
// Same parametrization as Bruneton's ground irradiance table (common/scattering_lut.glsl).
#include "atmosphere/atmosphere_sampling.glsl"
#include "common/scattering_lut.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D skyIrradiance;
layout(push_constant) uniform Push { int theta_samples; int march_steps; } push;

void main() {
  ivec2 size = imageSize(skyIrradiance);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float r, mu_s;
  rMuSFromIrradianceUv(atmosphere, (vec2(texel) + 0.5) / vec2(size), size, r, mu_s);
  r = clamp(r, atmosphere.bottom_radius + 1.0, atmosphere.top_radius - 1.0);
  vec3 origin = vec3(0.0, 0.0, r);
  vec3 sun = vec3(sqrt(max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);

  int thetaSamples = max(push.theta_samples, 1);
  int phiSamples = 2 * thetaSamples;
  int steps = max(push.march_steps, 1);
  float dTheta = 0.5 * kPi / float(thetaSamples);
  float dPhi = 2.0 * kPi / float(phiSamples);
  vec3 irradiance = vec3(0.0);
  for (int j = 0; j < thetaSamples; ++j) {
    float theta = (float(j) + 0.5) * dTheta;
    float mu = cos(theta);
    float pathLength = distanceToNearestAtmosphereBoundary(atmosphere, r, mu);
    for (int k = 0; k < phiSamples; ++k) {
      float phi = (float(k) + 0.5) * dPhi;
      vec3 dir = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), mu);
      float nu = dot(dir, sun);
      float phaseR = rayleighPhase(nu);
      float phaseM = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
      vec3 radiance = vec3(0.0);
      vec3 throughput = vec3(1.0);
      float tPrevious = 0.0;
      for (int i = 1; i <= steps; ++i) {
        float f = float(i) / float(steps);
        float tNext = pathLength * f * f;
        float dt = tNext - tPrevious;
        vec3 p = origin + dir * (0.5 * (tPrevious + tNext));
        tPrevious = tNext;
        float r_p = length(p);
        float mu_s_p = dot(p, sun) / r_p;
        vec3 rayleigh = rayleighScatteringAt(atmosphere, r_p);
        vec3 mie = mieScatteringAt(atmosphere, r_p);
        vec3 extinction = extinctionAt(atmosphere, r_p);
        vec3 sunLight = transmittanceToSun(transmittanceLut, atmosphere, r_p, mu_s_p) * atmosphere.solar_irradiance;
        vec3 source = (rayleigh * phaseR + mie * phaseM) * sunLight +
                      (rayleigh + mie) * multipleScattering(multipleScatteringLut, atmosphere, r_p, mu_s_p);
        vec3 stepTransmittance = exp(-extinction * dt);
        vec3 kappa = extinction * dt;
        vec3 integral = mix(dt * (1.0 - stepTransmittance) / max(kappa, vec3(1e-12)), vec3(dt), lessThan(kappa, vec3(1e-4)));
        radiance += throughput * source * integral;
        throughput *= stepTransmittance;
      }
      irradiance += radiance * (mu * sin(theta) * dTheta * dPhi);
    }
  }
  imageStore(skyIrradiance, texel, vec4(irradiance, 0.0));
}
