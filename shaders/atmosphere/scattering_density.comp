#version 450
#extension GL_GOOGLE_include_directive : require
// Bruneton 2017's precomputation, order n >= 2, step a: the scattering density
//   J_n(x, w) = ∫_sphere L_{n-1}(x, w_i) [ beta_R(x) p_R(w . w_i) + beta_M^s(x) p_M(w . w_i) ] dw_i
// (W m^-3 sr^-1 nm^-1: radiance per metre), where L_{n-1}(x, w_i) is the radiance of order n-1 that
// reaches x from direction w_i: from the tables, and, for directions that meet the ground, the ground's
// reflection of the order n-2 irradiance, T(x, ground) rho/pi E_{n-2}(ground) (order 0 = the sun).
// w_i runs over a midpoint grid of the sphere in (theta, phi): theta_samples x 2 theta_samples cells
// of solid angle sin(theta) dtheta dphi (Bruneton uses 16, so 512 directions).
//
// The incoming radiance depends on r, mu_s and w_i only, never on the view direction w. So one
// workgroup takes one (mu_s, r) pair: it gathers the incoming radiance of every w_i once into shared
// memory (the only texture reads), and then each invocation sums it against the phase functions for
// its share of the (mu, nu) texels, in a frame with the sun fixed at (sqrt(1 - mu_s^2), 0, mu_s).
// This reads the tables mu_size * nu_size = 1024 times less than a per-texel gather, and is exact:
// the same sum over the same directions.
#include "atmosphere/irradiance_sampling.glsl"
#include "atmosphere/scattering_sampling.glsl"

#define MAX_THETA_SAMPLES 16
#define MAX_DIRECTIONS (2 * MAX_THETA_SAMPLES * MAX_THETA_SAMPLES)

layout(local_size_x = 64) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler3D deltaRayleigh;   // order 1, Rayleigh (no phase)
layout(set = 0, binding = 3) uniform sampler3D deltaMie;        // order 1, Mie (no phase)
layout(set = 0, binding = 4) uniform sampler3D deltaMultiple;   // order n-1 >= 2, phase included
layout(set = 0, binding = 5) uniform sampler2D deltaIrradiance; // ground irradiance of order n-2
layout(set = 0, binding = 6, rgba32f) uniform writeonly image3D scatteringDensity;
layout(push_constant) uniform Push { ivec4 table_size; int order; int theta_samples; } push;

shared vec3 incomingRadiance[MAX_DIRECTIONS];  // L_{n-1}(w_i) dw_i
shared vec3 incomingDirection[MAX_DIRECTIONS];

void main() {
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  ScatteringTableSize tableSize = ScatteringTableSize(push.table_size.x, push.table_size.y, push.table_size.z, push.table_size.w);
  int i_mu_s = int(gl_WorkGroupID.x);
  int i_r = int(gl_WorkGroupID.y);
  float r, mu_unused, mu_s, nu_unused;
  bool hits_unused;
  scatteringTexelParameters(atmosphere, tableSize, ivec3(i_mu_s, 0, i_r), r, mu_unused, mu_s, nu_unused, hits_unused);
  float sin_s = sqrt(max(1.0 - mu_s * mu_s, 0.0));
  vec3 sun = vec3(sin_s, 0.0, mu_s);

  // 1. Gather L_{n-1}(w_i) dw_i for every direction.
  int thetaSamples = clamp(push.theta_samples, 1, MAX_THETA_SAMPLES);
  int phiSamples = 2 * thetaSamples;
  int directions = thetaSamples * phiSamples;
  float dTheta = kPi / float(thetaSamples);
  float dPhi = 2.0 * kPi / float(phiSamples);
  for (int i = int(gl_LocalInvocationIndex); i < directions; i += int(gl_WorkGroupSize.x)) {
    int j = i / phiSamples;
    int k = i - j * phiSamples;
    float theta = (float(j) + 0.5) * dTheta;
    float phi = (float(k) + 0.5) * dPhi;
    vec3 w_i = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
    float mu_i = w_i.z;
    float nu_i = dot(w_i, sun);
    bool hitsGround = rayIntersectsGround(atmosphere, r, mu_i);
    vec3 radiance;
    if (push.order == 2) {
      radiance = scatteringAt(deltaRayleigh, atmosphere, tableSize, r, mu_i, mu_s, nu_i, hitsGround) * rayleighPhase(nu_i) +
                 scatteringAt(deltaMie, atmosphere, tableSize, r, mu_i, mu_s, nu_i, hitsGround) *
                     cornetteShanksPhase(atmosphere.mie_phase_g, nu_i);
    } else {
      radiance = scatteringAt(deltaMultiple, atmosphere, tableSize, r, mu_i, mu_s, nu_i, hitsGround);
    }
    if (hitsGround) {
      // The ground point x + d w_i has up vector (x + d w_i) / R_b, so its sun cosine is
      // (r mu_s + d nu_i) / R_b; it reflects rho/pi times the irradiance it receives.
      float d = distanceToBottomAtmosphereBoundary(atmosphere, r, mu_i);
      float mu_s_ground = clampCosine((r * mu_s + d * nu_i) / atmosphere.bottom_radius);
      vec3 groundIrradiance = irradianceLookup(deltaIrradiance, atmosphere, atmosphere.bottom_radius, mu_s_ground);
      radiance += transmittanceBetween(transmittanceLut, atmosphere, r, mu_i, d, true) * atmosphere.ground_albedo / kPi *
                  groundIrradiance;
    }
    incomingRadiance[i] = radiance * sin(theta) * dTheta * dPhi;
    incomingDirection[i] = w_i;
  }
  barrier();

  // 2. Each (mu, nu) texel of this (mu_s, r): J = sum_i L_i dw_i [beta_R p_R + beta_M p_M](w . w_i).
  float h = r - atmosphere.bottom_radius;
  vec3 betaR = atmosphere.rayleigh_scattering * profileDensity(atmosphere.rayleigh_density, h);
  vec3 betaM = atmosphere.mie_scattering * profileDensity(atmosphere.mie_density, h);
  int texels = tableSize.mu * tableSize.nu;
  for (int t = int(gl_LocalInvocationIndex); t < texels; t += int(gl_WorkGroupSize.x)) {
    int i_mu = t / tableSize.nu;
    int i_nu = t - i_mu * tableSize.nu;
    ivec3 texel = ivec3(i_nu * tableSize.mu_s + i_mu_s, i_mu, i_r);
    float r_t, mu, mu_s_t, nu;
    bool hitsGround;
    scatteringTexelParameters(atmosphere, tableSize, texel, r_t, mu, mu_s_t, nu, hitsGround);
    // The view direction w in the sun's frame: w.z = mu and w . sun = nu give w.x; w.y >= 0 by the
    // mirror symmetry of the grid about the sun's vertical plane.
    float sin_mu = sqrt(max(1.0 - mu * mu, 0.0));
    float wx = sin_s > 1e-5 ? clamp((nu - mu * mu_s) / sin_s, -sin_mu, sin_mu) : sin_mu;
    vec3 w = vec3(wx, sqrt(max(1.0 - mu * mu - wx * wx, 0.0)), mu);
    vec3 rayleighSum = vec3(0.0);
    vec3 mieSum = vec3(0.0);
    for (int i = 0; i < directions; ++i) {
      float cos_angle = dot(w, incomingDirection[i]);
      rayleighSum += incomingRadiance[i] * rayleighPhase(cos_angle);
      mieSum += incomingRadiance[i] * cornetteShanksPhase(atmosphere.mie_phase_g, cos_angle);
    }
    imageStore(scatteringDensity, texel, vec4(betaR * rayleighSum + betaM * mieSum, 0.0));
  }
}
