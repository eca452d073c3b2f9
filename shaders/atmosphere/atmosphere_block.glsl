// atmosphere_block.glsl (GPU only): the atmosphere parameters as a std140 uniform block of vec4s,
// unpacked into the shared AtmosphereParameters struct. The C++ side packs it in
// atmosphere/atmosphere_gpu.cpp (packAtmosphereBlock); the layout below is the contract.
#ifndef FIRMAMENT_ATMOSPHERE_BLOCK_GLSL
#define FIRMAMENT_ATMOSPHERE_BLOCK_GLSL

#include "common/atmosphere_lut.glsl"

#ifndef ATMOSPHERE_BLOCK_BINDING
#define ATMOSPHERE_BLOCK_BINDING 0
#endif

layout(std140, set = 0, binding = ATMOSPHERE_BLOCK_BINDING) uniform AtmosphereBlock {
  vec4 radii;                  // bottom_radius, top_radius, sun_angular_radius, mie_phase_g
  vec4 solar_irradiance;       // xyz; w = mu_s_min
  vec4 rayleigh_scattering;    // xyz
  vec4 mie_scattering;         // xyz
  vec4 mie_extinction;         // xyz
  vec4 absorption_extinction;  // xyz
  vec4 ground_albedo;          // xyz
  vec4 profiles[8];            // rayleigh, mie, absorption; 2 layers each of
                               // (width, exp_term, exp_scale, linear_term, constant_term), flat;
                               // profiles[7].zw: the aerosol phase's Legendre moments a_1, a_2
  vec4 sky_radiance_to_rgb[3]; // columns of the 3x3 matrix: linear Rec.709 (cd m^-2) per unit radiance
  vec4 sun_radiance_to_rgb[3]; // the same for the sun's direct radiance
} atmosphereBlock;

// Legendre moments a_1, a_2 of the aerosol phase (atmosphere/atmosphere_block.cpp).
vec2 miePhaseMoments() { return atmosphereBlock.profiles[7].zw; }

float profileValue(int k) { return atmosphereBlock.profiles[k / 4][k % 4]; }

DensityLayer layerFromBlock(int first) {
  DensityLayer layer;
  layer.width = profileValue(first);
  layer.exp_term = profileValue(first + 1);
  layer.exp_scale = profileValue(first + 2);
  layer.linear_term = profileValue(first + 3);
  layer.constant_term = profileValue(first + 4);
  return layer;
}

AtmosphereParameters atmosphereFromBlock() {
  AtmosphereParameters a;
  a.bottom_radius = atmosphereBlock.radii.x;
  a.top_radius = atmosphereBlock.radii.y;
  a.sun_angular_radius = atmosphereBlock.radii.z;
  a.mie_phase_g = atmosphereBlock.radii.w;
  a.solar_irradiance = atmosphereBlock.solar_irradiance.xyz;
  a.mu_s_min = atmosphereBlock.solar_irradiance.w;
  a.rayleigh_scattering = atmosphereBlock.rayleigh_scattering.xyz;
  a.mie_scattering = atmosphereBlock.mie_scattering.xyz;
  a.mie_extinction = atmosphereBlock.mie_extinction.xyz;
  a.absorption_extinction = atmosphereBlock.absorption_extinction.xyz;
  a.ground_albedo = atmosphereBlock.ground_albedo.xyz;
  a.rayleigh_density.layer0 = layerFromBlock(0);
  a.rayleigh_density.layer1 = layerFromBlock(5);
  a.mie_density.layer0 = layerFromBlock(10);
  a.mie_density.layer1 = layerFromBlock(15);
  a.absorption_density.layer0 = layerFromBlock(20);
  a.absorption_density.layer1 = layerFromBlock(25);
  return a;
}

mat3 skyRadianceToRgb() {
  return mat3(atmosphereBlock.sky_radiance_to_rgb[0].xyz, atmosphereBlock.sky_radiance_to_rgb[1].xyz,
              atmosphereBlock.sky_radiance_to_rgb[2].xyz);
}

mat3 sunRadianceToRgb() {
  return mat3(atmosphereBlock.sun_radiance_to_rgb[0].xyz, atmosphereBlock.sun_radiance_to_rgb[1].xyz,
              atmosphereBlock.sun_radiance_to_rgb[2].xyz);
}

#endif  // FIRMAMENT_ATMOSPHERE_BLOCK_GLSL
