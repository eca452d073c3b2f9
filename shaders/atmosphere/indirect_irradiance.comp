#version 450
#extension GL_GOOGLE_include_directive : require
// Bruneton 2017's precomputation, order n >= 2, step b: the irradiance that scattered light of order
// k = n - 1 brings to a horizontal surface at (r, mu_s),
//   E_k(r, mu_s) = ∫_upper hemisphere L_k(r, w_i) cos(theta_i) dw_i          (W m^-2 nm^-1),
// over a midpoint grid of theta_samples (theta in [0, pi/2]) x 4 theta_samples (phi in [0, 2 pi])
// cells (Bruneton: 16 x 64). E_k becomes the delta irradiance that lights the ground for order n + 1,
// and is added to the ground irradiance table (the sky's irradiance, orders 1..N-1).
#include "atmosphere/scattering_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler3D deltaRayleigh;
layout(set = 0, binding = 2) uniform sampler3D deltaMie;
layout(set = 0, binding = 3) uniform sampler3D deltaMultiple;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D deltaIrradiance;
layout(set = 0, binding = 5, rgba32f) uniform image2D irradiance;
layout(push_constant) uniform Push { ivec4 table_size; int light_order; int theta_samples; } push;

void main() {
  ivec2 size = imageSize(irradiance);
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= size.x || texel.y >= size.y) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  ScatteringTableSize tableSize = ScatteringTableSize(push.table_size.x, push.table_size.y, push.table_size.z, push.table_size.w);
  float r, mu_s;
  rMuSFromIrradianceUv(atmosphere, (vec2(texel) + 0.5) / vec2(size), size, r, mu_s);
  vec3 sun = vec3(sqrt(max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);

  int thetaSamples = max(push.theta_samples, 1);
  int phiSamples = 4 * thetaSamples;
  float dTheta = 0.5 * kPi / float(thetaSamples);
  float dPhi = 2.0 * kPi / float(phiSamples);
  vec3 result = vec3(0.0);
  for (int j = 0; j < thetaSamples; ++j) {
    float theta = (float(j) + 0.5) * dTheta;
    float mu_i = cos(theta);
    float weight = mu_i * sin(theta) * dTheta * dPhi;  // cos(theta) dw
    for (int k = 0; k < phiSamples; ++k) {
      float phi = (float(k) + 0.5) * dPhi;
      vec3 w_i = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), mu_i);
      float nu_i = dot(w_i, sun);
      vec3 radiance;
      if (push.light_order == 1) {
        radiance = scatteringAt(deltaRayleigh, atmosphere, tableSize, r, mu_i, mu_s, nu_i, false) * rayleighPhase(nu_i) +
                   scatteringAt(deltaMie, atmosphere, tableSize, r, mu_i, mu_s, nu_i, false) *
                       cornetteShanksPhase(atmosphere.mie_phase_g, nu_i);
      } else {
        radiance = scatteringAt(deltaMultiple, atmosphere, tableSize, r, mu_i, mu_s, nu_i, false);
      }
      result += radiance * weight;
    }
  }
  imageStore(deltaIrradiance, texel, vec4(result, 0.0));
  imageStore(irradiance, texel, imageLoad(irradiance, texel) + vec4(result, 0.0));
}
