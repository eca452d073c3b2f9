#version 450
#extension GL_GOOGLE_include_directive : require
// Bruneton 2017's precomputation, order n >= 2, step c: the radiance of order n arriving at the ray's
// start, the scattering density integrated along the ray with the transmittance to it,
//   L_n(r, mu, mu_s, nu) = ∫_0^D T(x, y) J_n(y, w) dy          (W m^-2 sr^-1 nm^-1),
// where y = x + d w has radius r_d and cosines mu_d, mu_s_d (nu is unchanged along a straight ray),
// by the trapezoidal rule with `steps` intervals. L_n becomes the delta table that the next order
// scatters, and L_n / p_R(nu) is added to the accumulated table, which thereby stores every order
// under the Rayleigh phase function: a lookup multiplies the sum by p_R(nu) once (Bruneton's choice;
// multiple scattering is smooth in nu, so the division costs nothing in accuracy).
#include "atmosphere/scattering_sampling.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler3D scatteringDensity;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image3D deltaMultiple;
layout(set = 0, binding = 4, rgba32f) uniform image3D scattering;
layout(push_constant) uniform Push { ivec4 table_size; int steps; } push;

void main() {
  ivec3 size = imageSize(deltaMultiple);
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(texel, size))) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  ScatteringTableSize tableSize = ScatteringTableSize(push.table_size.x, push.table_size.y, push.table_size.z, push.table_size.w);
  float r, mu, mu_s, nu;
  bool hitsGround;
  scatteringTexelParameters(atmosphere, tableSize, texel, r, mu, mu_s, nu, hitsGround);

  int steps = max(push.steps, 1);
  float dx = distanceToNearestAtmosphereBoundary(r, mu, atmosphere.bottom_radius, atmosphere.top_radius, hitsGround) / float(steps);
  vec3 sum = vec3(0.0);
  for (int i = 0; i <= steps; ++i) {
    float d = float(i) * dx;
    float r_d, mu_d, mu_s_d;
    pointAlongRay(r, mu, mu_s, nu, d, r_d, mu_d, mu_s_d);
    vec3 density = scatteringAt(scatteringDensity, atmosphere, tableSize, r_d, mu_d, mu_s_d, nu, hitsGround);
    float weight = (i == 0 || i == steps) ? 0.5 : 1.0;
    sum += weight * transmittanceBetween(transmittanceLut, atmosphere, r, mu, d, hitsGround) * density;
  }
  vec3 radiance = sum * dx;
  imageStore(deltaMultiple, texel, vec4(radiance, 0.0));
  imageStore(scattering, texel, imageLoad(scattering, texel) + vec4(radiance / rayleighPhase(nu), 0.0));
}
