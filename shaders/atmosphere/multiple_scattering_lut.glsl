// Multiple-scattering table Psi_ms(r, mu_s): the mean radiance of all light that has scattered at
// least once, arriving at a point from every direction. The render adds sigma_s Psi_ms per step, i.e.
// it scatters that light once more with an isotropic phase (Hillaire 2020, "A Scalable and Production
// Ready Sky and Atmosphere Rendering Technique", section 5.5).
//
// Orders. With L_k(x, w) the radiance at x from direction w of light scattered exactly k times and
// J_k(x) = (1/4pi) ∫_sphere L_k(x, w) dw its mean, Psi_ms = sum_{k >= 1} J_k. In a spherically
// symmetric atmosphere J_k depends on (r, mu_s) only, so each order is one table:
//   L_1(x, w) = ∫_0^D T(x, y) sigma_s(y) p(nu) E_sun T_sun(y) dt + T(x, g) rho/pi E_sun T_sun(g) mu_s(g)
//   L_k(x, w) = ∫_0^D T(x, y) sigma_s(y) J_{k-1}(y) dt + T(x, g) rho/pi E_{k-1}(g)     (k >= 2)
//   E_k(g)    = ∫_upper hemisphere L_k(g, w) cos(theta) dw                     (irradiance at the ground)
// p is the real phase (Rayleigh and Cornette-Shanks for Mie, split by their scattering coefficients);
// from the second scattering on the phase is taken as isotropic (the only approximation besides the
// quadrature): sigma_s J_{k-1} is the isotropic scattering of the mean radiance.
// Hillaire's form is the case of one order: it also assumes every point near x receives the same
// light as x, so the orders form a geometric series of ratio f_ms,
//   f_ms = (1/4pi) ∫_sphere ∫_0^D T sigma_s dt dw,   Psi_ms = J_1 / (1 - f_ms)
// (he also uses an isotropic phase for J_1). That neighbourhood assumption is what fails at a low sun:
// the air towards the sun's horizon is lit more than the air below, and at sun zenith 88 deg it left
// Psi_ms 16-22 % short (docs/atmosphere.md). Here `orders` tables are iterated explicitly, each reading
// the previous one at the points y of its rays, and the orders past the last are the geometric tail
// J_N q / (1 - q) with q = J_N / J_{N-1} measured per texel (f_ms when there is one order).
//
// Anisotropy. The render scatters Psi_ms into the view with the real phase functions where it pays:
// with the radiance field written in real spherical harmonics up to l = 2, L = sum c_lm Y_lm, the
// Funk-Hecke theorem gives ∫ p(w.v) L(w) dw = sum a_l c_lm Y_lm(v), a_l = 2 pi ∫ p(mu) P_l(mu) dmu the
// phase's Legendre moments (a_0 = 1; Rayleigh a_1 = 0, a_2 = 1/10; the aerosol's from its phase). The
// field is symmetric about the plane of the zenith and the sun, so in the local frame (z up, y towards
// the sun's azimuth) five coefficients besides c_00 remain: Y_1y, Y_1z, Y_2yz, Y_2zz, Y_2(xx-yy)
// (common/atmosphere_lut.glsl). Their sums over the orders are the anisotropy table (size x size x 5);
// c_00 is Psi_ms itself (J = c_00 Y_00). Without it (one order) the render is Hillaire's isotropic one.
// The table is stored as c_lm / Psi_ms, packed into four RGBA tiles (atmosphere/atmosphere_sampling.glsl).
//
// Two compiled variants (FIRST_ORDER 1: multiple_scattering_lut.comp, the sun's light; 0:
// multiple_scattering_order.comp, reading the previous order): a uniform branch would run both sides
// on lavapipe (docs/gpu.md).
//
// Directions: a stratification of the sphere, uniform in the cosine of the zenith angle and in azimuth,
// so each sample stands for the same solid angle. The march along a direction is smooth over its cell;
// the phase is not (the aerosol's forward peak is a few degrees wide), so it is averaged over the cell
// (kPhaseSubsamples per axis) rather than taken at the cell's centre.
#ifndef FIRST_ORDER
#error "define FIRST_ORDER before including atmosphere/multiple_scattering_lut.glsl"
#endif
#include "atmosphere/atmosphere_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2, rgba32f) uniform image2D multipleScatteringLut;  // Psi_ms, summed order by order
layout(set = 0, binding = 3) uniform sampler2D previousOrder;                  // J_{k-1}(r, mu_s) (k >= 2)
layout(set = 0, binding = 4) uniform sampler2D previousGroundIrradiance;       // E_{k-1}(mu_s), width x 1 (k >= 2)
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D currentOrder;             // J_k
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D currentGroundIrradiance;  // E_k (row 0 writes it)
layout(set = 0, binding = 7, rgba32f) uniform image2D anisotropyLut;  // sum of c_lm, l >= 1, in kAnisotropyTiles tiles (see above)
layout(push_constant) uniform Push {
  int theta_samples;
  int phi_samples;
  int march_steps;
  int order;  // k: 1 = light from the sun
  int last;   // 1: add the tail of the orders past this one
  int real_phase;  // first order: 1 = Rayleigh and aerosol phase functions, 0 = isotropic (Hillaire 2020)
} push;

const int kPhaseSubsamples = 4;

// Means over the cell of directions cos(theta) in [c0, c1], phi in [phi0, phi1] (sun in the y-z plane):
// of the Rayleigh and aerosol phase functions (x, y of `phase`), and of the five anisotropy harmonics.
void cellMeans(AtmosphereParameters atmosphere, vec3 sun, float c0, float c1, float phi0, float phi1,
               bool with_phase, out vec2 phase, out float harmonics[kAnisotropyTerms]) {
  phase = vec2(0.0);
  for (int h = 0; h < kAnisotropyTerms; ++h) harmonics[h] = 0.0;
  for (int a = 0; a < kPhaseSubsamples; ++a) {
    float c = mix(c0, c1, (float(a) + 0.5) / float(kPhaseSubsamples));
    float s = sqrt(max(1.0 - c * c, 0.0));
    for (int b = 0; b < kPhaseSubsamples; ++b) {
      float phi = mix(phi0, phi1, (float(b) + 0.5) / float(kPhaseSubsamples));
      vec3 w = vec3(s * cos(phi), s * sin(phi), c);
      if (with_phase) {
        float nu = dot(w, sun);
        phase += vec2(rayleighPhase(nu), cornetteShanksPhase(atmosphere.mie_phase_g, nu));
      }
      for (int h = 0; h < kAnisotropyTerms; ++h) harmonics[h] += anisotropyHarmonic(h, w);
    }
  }
  float n = float(kPhaseSubsamples * kPhaseSubsamples);
  phase /= n;
  for (int h = 0; h < kAnisotropyTerms; ++h) harmonics[h] /= n;
}

vec3 previousOrderAt(AtmosphereParameters atmosphere, float r, float mu_s) {
  ivec2 size = textureSize(previousOrder, 0);
  return decodeLog(textureLod(previousOrder, multipleScatteringUv(atmosphere, r, mu_s, size), 0.0).rgb);
}

vec3 previousGroundIrradianceAt(AtmosphereParameters atmosphere, float mu_s) {
  ivec2 size = textureSize(previousOrder, 0);
  return textureLod(previousGroundIrradiance, vec2(multipleScatteringUv(atmosphere, atmosphere.bottom_radius, mu_s, size).x, 0.5), 0.0).rgb;
}

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
  float cell = 4.0 * kPi / float(n_theta * n_phi);  // solid angle of one direction's cell
  vec3 mean_radiance = vec3(0.0);
  vec3 transfer = vec3(0.0);
  vec3 ground_irradiance = vec3(0.0);
  vec3 moments[kAnisotropyTerms];
  for (int h = 0; h < kAnisotropyTerms; ++h) moments[h] = vec3(0.0);
  for (int i = 0; i < n_theta; ++i) {
    float c0 = 1.0 - 2.0 * float(i) / float(n_theta);
    float c1 = 1.0 - 2.0 * float(i + 1) / float(n_theta);
    float cos_theta = 0.5 * (c0 + c1);
    float sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    float mu = cos_theta;
    bool hits_ground = rayIntersectsGround(atmosphere, r, mu);
    float path_length = distanceToNearestAtmosphereBoundary(atmosphere, r, mu);
    float dt = path_length / float(push.march_steps);
    for (int j = 0; j < n_phi; ++j) {
      float phi0 = 2.0 * kPi * float(j) / float(n_phi);
      float phi1 = 2.0 * kPi * float(j + 1) / float(n_phi);
      float phi = 0.5 * (phi0 + phi1);
      vec3 dir = vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
      vec2 phase;
      float harmonics[kAnisotropyTerms];
      cellMeans(atmosphere, sun, c0, c1, phi0, phi1, FIRST_ORDER != 0, phase, harmonics);
#if FIRST_ORDER
      if (push.real_phase == 0) phase = vec2(1.0 / (4.0 * kPi));
#endif
      vec3 throughput = vec3(1.0);
      vec3 radiance = vec3(0.0);
      vec3 l_f = vec3(0.0);
      for (int s = 0; s < push.march_steps; ++s) {
        vec3 p = origin + dir * ((float(s) + 0.5) * dt);
        float r_p = length(p);
        float mu_s_p = dot(p, sun) / r_p;
        vec3 rayleigh = rayleighScatteringAt(atmosphere, r_p);
        vec3 mie = mieScatteringAt(atmosphere, r_p);
        vec3 extinction = extinctionAt(atmosphere, r_p);
        vec3 step_transmittance = exp(-extinction * dt);
        // Energy-conserving integration over the step (Hillaire 2016): ∫_0^dt e^(-sigma_t x) dx,
        // written as dt * (1 - e^(-k)) / k so it stays exact as k = sigma_t dt -> 0.
        vec3 k = extinction * dt;
        vec3 integral = mix(dt * (1.0 - step_transmittance) / max(k, vec3(1e-12)), vec3(dt), lessThan(k, vec3(1e-4)));
#if FIRST_ORDER
        vec3 sun_light = transmittanceToSun(transmittanceLut, atmosphere, r_p, mu_s_p) * atmosphere.solar_irradiance;
        vec3 source = (rayleigh * phase.x + mie * phase.y) * sun_light;
#else
        vec3 source = (rayleigh + mie) * previousOrderAt(atmosphere, r_p, mu_s_p);
#endif
        radiance += throughput * source * integral;
        l_f += throughput * (rayleigh + mie) * integral;
        throughput *= step_transmittance;
      }
      if (hits_ground) {
        // Lambertian ground: radiance albedo/pi times the irradiance of the order before (the sun's
        // direct light for the first order).
        vec3 p = origin + dir * path_length;
        float r_g = length(p);
        float mu_s_g = dot(p, sun) / r_g;
#if FIRST_ORDER
        vec3 irradiance = transmittanceToSun(transmittanceLut, atmosphere, r_g, mu_s_g) * atmosphere.solar_irradiance * max(mu_s_g, 0.0);
#else
        vec3 irradiance = previousGroundIrradianceAt(atmosphere, mu_s_g);
#endif
        radiance += throughput * atmosphere.ground_albedo / kPi * irradiance;
      }
      mean_radiance += radiance;
      transfer += l_f;
      if (cos_theta > 0.0) ground_irradiance += radiance * cos_theta * cell;
      for (int h = 0; h < kAnisotropyTerms; ++h) moments[h] += radiance * harmonics[h] * cell;
    }
  }
  float samples = float(n_theta * n_phi);
  vec3 j_k = mean_radiance / samples;
  transfer /= samples;
  // The orders past this one, as a geometric series (it converges: a fraction of the light is lost to
  // space, the ground and absorption every order; the clamps guard albedo 1 without absorption and
  // texels where an order is numerically zero).
  vec3 tail = vec3(0.0);
  vec3 tail_factor = vec3(0.0);  // the orders past this one, relative to this one
  if (push.last != 0) {
    vec3 q = transfer;
#if !FIRST_ORDER
    vec3 previous = decodeLog(texelFetch(previousOrder, texel, 0).rgb);
    q = mix(transfer, j_k / max(previous, vec3(1e-30)), greaterThan(previous, vec3(1e-30)));
#endif
    q = clamp(q, vec3(0.0), vec3(0.98));
    tail_factor = q / (vec3(1.0) - q);
    tail = j_k * tail_factor;
  }
  // The table sums the orders linearly; the last order stores ln Psi_ms for the readers and the
  // anisotropy as c_lm / Psi_ms, so both interpolate well across the Earth's shadow (see
  // atmosphere/atmosphere_sampling.glsl). The scratch order J_k is stored as a logarithm too.
#if FIRST_ORDER
  vec3 psi = j_k + tail;
#else
  vec3 psi = imageLoad(multipleScatteringLut, texel).rgb + j_k + tail;
#endif
  imageStore(multipleScatteringLut, texel, vec4(push.last != 0 ? encodeLog(psi) : psi, 1.0));
  vec3 sums[kAnisotropyTerms];
#if FIRST_ORDER
  for (int h = 0; h < kAnisotropyTerms; ++h) sums[h] = vec3(0.0);
#else
  unpackAnisotropy(imageLoad(anisotropyLut, texel), imageLoad(anisotropyLut, texel + ivec2(size.x, 0)),
                   imageLoad(anisotropyLut, texel + ivec2(2 * size.x, 0)), imageLoad(anisotropyLut, texel + ivec2(3 * size.x, 0)), sums);
#endif
  for (int h = 0; h < kAnisotropyTerms; ++h) {
    // Hillaire's form (one order, isotropic phase) has no anisotropy.
    if (push.real_phase != 0) sums[h] += moments[h] * (vec3(1.0) + tail_factor);
    if (push.last != 0) sums[h] = mix(vec3(0.0), sums[h] / max(psi, vec3(1e-30)), greaterThan(psi, vec3(1e-30)));
  }
  vec4 tiles[kAnisotropyTiles];
  packAnisotropy(sums, tiles[0], tiles[1], tiles[2], tiles[3]);
  for (int t = 0; t < kAnisotropyTiles; ++t) imageStore(anisotropyLut, texel + ivec2(t * size.x, 0), tiles[t]);
  imageStore(currentOrder, texel, vec4(encodeLog(j_k), 1.0));
  if (texel.y == 0) imageStore(currentGroundIrradiance, ivec2(texel.x, 0), vec4(ground_irradiance, 1.0));
}
