#version 450
#extension GL_GOOGLE_include_directive : require
// Bruneton 2017's precomputation, step 2: single scattering into the 4D table. For the texel's ray
// from radius r along (mu), with the sun at (mu_s, nu), and D the distance to the boundary it ends on,
//   S_R(r, mu, mu_s, nu) = E_sun beta_R ∫_0^D T(x, y) T_sun(y) d_R(y) dy
//   S_M(r, mu, mu_s, nu) = E_sun beta_M^s ∫_0^D T(x, y) T_sun(y) d_M(y) dy
// (W m^-2 nm^-1; times a phase function, 1/sr, they are radiances). The phase functions are applied
// at lookup, where nu is exact, rather than baked in at the table's 8 nu samples, which would blur the
// Mie forward peak. The trapezoidal rule with `steps` intervals integrates each ray.
// Outputs: delta Rayleigh and delta Mie (the first order, read by the next passes); the Rayleigh part
// also initialises the accumulated scattering table. Single Mie stays in its own table (no alpha-channel
// extrapolation).
#include "atmosphere/scattering_sampling.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image3D deltaRayleigh;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image3D deltaMie;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image3D scattering;
layout(push_constant) uniform Push { ivec4 table_size; int steps; } push;

void main() {
  ivec3 size = imageSize(deltaRayleigh);
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(texel, size))) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  ScatteringTableSize tableSize = ScatteringTableSize(push.table_size.x, push.table_size.y, push.table_size.z, push.table_size.w);
  float r, mu, mu_s, nu;
  bool hitsGround;
  scatteringTexelParameters(atmosphere, tableSize, texel, r, mu, mu_s, nu, hitsGround);

  int steps = max(push.steps, 1);
  float dx = distanceToNearestAtmosphereBoundary(r, mu, atmosphere.bottom_radius, atmosphere.top_radius, hitsGround) / float(steps);
  vec3 rayleighSum = vec3(0.0);
  vec3 mieSum = vec3(0.0);
  for (int i = 0; i <= steps; ++i) {
    float d = float(i) * dx;
    float r_d, mu_d, mu_s_d;
    pointAlongRay(r, mu, mu_s, nu, d, r_d, mu_d, mu_s_d);
    vec3 transmittance = transmittanceBetween(transmittanceLut, atmosphere, r, mu, d, hitsGround) *
                         transmittanceToSun(transmittanceLut, atmosphere, r_d, mu_s_d);
    float h = r_d - atmosphere.bottom_radius;
    float weight = (i == 0 || i == steps) ? 0.5 : 1.0;
    rayleighSum += weight * transmittance * profileDensity(atmosphere.rayleigh_density, h);
    mieSum += weight * transmittance * profileDensity(atmosphere.mie_density, h);
  }
  vec3 rayleigh = rayleighSum * dx * atmosphere.solar_irradiance * atmosphere.rayleigh_scattering;
  vec3 mie = mieSum * dx * atmosphere.solar_irradiance * atmosphere.mie_scattering;
  imageStore(deltaRayleigh, texel, vec4(rayleigh, 0.0));
  imageStore(deltaMie, texel, vec4(mie, 0.0));
  imageStore(scattering, texel, vec4(rayleigh, 0.0));
}
