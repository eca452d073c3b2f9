#pragma once
// Packs AtmosphereParameters into the std140 uniform block that shaders/atmosphere/atmosphere_block.glsl
// unpacks: the one place the GPU layout is written down on the C++ side.
#include <array>

#include <glm/glm.hpp>

#include "common/atmosphere_medium.glsl"

namespace firmament {

struct AtmosphereBlock {
  float radii[4];            // bottom_radius, top_radius, sun_angular_radius, mie_phase_g
  float solarIrradiance[4];  // xyz; w = mu_s_min
  float rayleighScattering[4];
  float mieScattering[4];
  float mieExtinction[4];
  float absorptionExtinction[4];
  float groundAlbedo[4];
  float profiles[8][4];          // 3 profiles x 2 layers x 5 values, flat; then the aerosol phase's
                                 // Legendre moments a_1, a_2 (profiles[7].zw)
  float skyRadianceToRgb[3][4];  // columns
  float sunRadianceToRgb[3][4];  // columns
};
static_assert(sizeof(AtmosphereBlock) == 21 * 16, "std140 layout: 21 vec4");

// radianceToRgb matrices map radiance at the three wavelengths to linear Rec.709 in cd m^-2.
AtmosphereBlock packAtmosphereBlock(const shared::AtmosphereParameters& atmosphere, const glm::dmat3& skyRadianceToRgb,
                                    const glm::dmat3& sunRadianceToRgb);

}  // namespace firmament
