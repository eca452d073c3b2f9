// irradiance_sampling.glsl (GPU only): irradiance on a horizontal surface, E_sky(r, mu_s),
// from a ground irradiance table (Bruneton's, or the f_ms path's; same parametrization, defined in
// common/scattering_lut.glsl). Units: W m^-2 nm^-1 per wavelength.
#ifndef FIRMAMENT_IRRADIANCE_SAMPLING_GLSL
#define FIRMAMENT_IRRADIANCE_SAMPLING_GLSL

#include "atmosphere/atmosphere_block.glsl"
#include "common/scattering_lut.glsl"

vec3 irradianceLookup(sampler2D irradianceTable, AtmosphereParameters atmosphere, float r, float mu_s) {
  ivec2 size = textureSize(irradianceTable, 0);
  return textureLod(irradianceTable, irradianceUvFromRMuS(atmosphere, r, mu_s, size), 0.0).rgb;
}

#endif  // FIRMAMENT_IRRADIANCE_SAMPLING_GLSL
