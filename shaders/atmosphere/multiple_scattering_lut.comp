#version 450
#extension GL_GOOGLE_include_directive : require
// Multiple-scattering LUT (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere
// Rendering Technique", section 5.5). For a point at radius r lit by the sun at cosine mu_s, and
// assuming (a) an isotropic phase for orders >= 2 and (b) the same second-order radiance reaching
// every point of a neighbourhood, the infinite sum of orders is a geometric series:
//   L_2nd = (1/4pi) ∫_sphere L'(x, -w) dw   second order with isotropic phase (plus ground bounce)
//   f_ms  = (1/4pi) ∫_sphere L_f(x, -w) dw   fraction of light scattered back to x per order
//   Psi_ms = L_2nd / (1 - f_ms)
// Directions: a stratification of the sphere, uniform in the cosine of the zenith angle and in azimuth,
// so each sample stands for the same solid angle and the averages are plain means. The integrand
// changes fast with the zenith angle (path lengths near the horizon) and slowly with the azimuth (only
// through the sun's direction), so zenith bands matter: 32 x 2 directions measured a -0.6 % luminance
// bias against the reference at noon where 8 x 8 gave -1.7 % for the same cost (docs/atmosphere.md).
#include "atmosphere/atmosphere_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D multipleScatteringLut;
layout(push_constant) uniform Push { int theta_samples; int phi_samples; int march_steps; } push;

const float kIsotropicPhase = 1.0 / (4.0 * kPi);

void main() {
  ivec2 size = imageSize(multipleScatteringLut);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  float r, mu_s;
  rMuSFromMultipleScatteringUv(atmosphere, (vec2(texel) + 0.5) / vec2(size), size, r, mu_s);
  // Keep the point strictly inside the shell so both boundaries are well defined.
  r = clamp(r, atmosphere.bottom_radius + 1.0, atmosphere.top_radius - 1.0);
  vec3 origin = vec3(0.0, 0.0, r);
  vec3 sun = vec3(0.0, sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s);

  int n_theta = max(push.theta_samples, 1);
  int n_phi = max(push.phi_samples, 1);
  vec3 second_order = vec3(0.0);
  vec3 transfer = vec3(0.0);
  for (int i = 0; i < n_theta; ++i) {
    for (int j = 0; j < n_phi; ++j) {
      float cos_theta = 1.0 - 2.0 * (float(i) + 0.5) / float(n_theta);
      float phi = 2.0 * kPi * (float(j) + 0.5) / float(n_phi);
      float sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
      vec3 dir = vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
      float mu = cos_theta;
      bool hits_ground = rayIntersectsGround(atmosphere, r, mu);
      float path_length = distanceToNearestAtmosphereBoundary(atmosphere, r, mu);
      float dt = path_length / float(push.march_steps);
      vec3 throughput = vec3(1.0);
      vec3 l_2nd = vec3(0.0);
      vec3 l_f = vec3(0.0);
      for (int s = 0; s < push.march_steps; ++s) {
        vec3 p = origin + dir * ((float(s) + 0.5) * dt);
        float r_p = length(p);
        float mu_s_p = dot(p, sun) / r_p;
        vec3 scattering = rayleighScatteringAt(atmosphere, r_p) + mieScatteringAt(atmosphere, r_p);
        vec3 extinction = extinctionAt(atmosphere, r_p);
        vec3 step_transmittance = exp(-extinction * dt);
        // Energy-conserving integration over the step (Hillaire 2016): ∫_0^dt e^(-sigma_t x) dx,
        // written as dt * (1 - e^(-k)) / k so it stays exact as k = sigma_t dt -> 0.
        vec3 k = extinction * dt;
        vec3 integral = mix(dt * (1.0 - step_transmittance) / max(k, vec3(1e-12)), vec3(dt), lessThan(k, vec3(1e-4)));
        vec3 sun_light = transmittanceToSun(transmittanceLut, atmosphere, r_p, mu_s_p) * atmosphere.solar_irradiance;
        l_2nd += throughput * scattering * sun_light * kIsotropicPhase * integral;
        l_f += throughput * scattering * integral;
        throughput *= step_transmittance;
      }
      if (hits_ground) {
        // Lambertian ground lit by the sun: radiance albedo/pi * E_sun T_sun max(mu_s, 0).
        vec3 p = origin + dir * path_length;
        float r_g = length(p);
        float mu_s_g = dot(p, sun) / r_g;
        vec3 sun_light = transmittanceToSun(transmittanceLut, atmosphere, r_g, mu_s_g) * atmosphere.solar_irradiance;
        l_2nd += throughput * atmosphere.ground_albedo / kPi * sun_light * max(mu_s_g, 0.0);
      }
      second_order += l_2nd;
      transfer += l_f;
    }
  }
  float samples = float(n_theta * n_phi);
  second_order /= samples;
  transfer /= samples;
  // The geometric series converges because f_ms < 1 (a fraction of the light is lost to space,
  // the ground and absorption); clamp guards pathological parameters (albedo 1, no absorption).
  vec3 psi = second_order / max(vec3(1.0) - transfer, vec3(1e-4));
  imageStore(multipleScatteringLut, texel, vec4(psi, 1.0));
}
