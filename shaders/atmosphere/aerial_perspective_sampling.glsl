// aerial_perspective_sampling.glsl (GPU only): reading the aerial-perspective volume
// (common/aerial_perspective.glsl has its layout; sky/aerial_perspective_volume.comp writes it): the
// air between the camera and distance d along the ray through image point `pixel`.
#ifndef FIRMAMENT_AERIAL_PERSPECTIVE_SAMPLING_GLSL
#define FIRMAMENT_AERIAL_PERSPECTIVE_SAMPLING_GLSL

#include "common/aerial_perspective.glsl"

// pixel: image point in pixel units (a pixel's centre is its index + 0.5); image: width, height;
// volume: linear filtering, clamp to edge; maxDistance: the volume's D (m); miePhase: the aerosol
// phase function p_M(nu) of this pixel's ray (the volume stores the aerosols' light without it).
// Out: the in-scattered light (linear Rec.709 cd/m^2, this batch's wavelengths) and the
// transmittance (this batch's three wavelengths). Three trilinear fetches.
void aerialPerspectiveLookup(sampler3D volume, vec2 pixel, ivec2 image, float d, float maxDistance, float miePhase,
                             out vec3 light, out vec3 transmittance) {
  ivec3 size = textureSize(volume, 0);
  int columns = size.x / kAerialTiles;
  vec2 z = aerialDepthCoordinate(d, size.z, maxDistance);
  float y = aerialTileY(pixel.y, image.y, size.y);
  vec3 skylike = textureLod(volume, vec3(aerialTileX(pixel.x, image.x, columns, 0), y, z.x), 0.0).rgb;
  vec3 aerosol = textureLod(volume, vec3(aerialTileX(pixel.x, image.x, columns, 1), y, z.x), 0.0).rgb;
  vec3 through = textureLod(volume, vec3(aerialTileX(pixel.x, image.x, columns, 2), y, z.x), 0.0).rgb;
  light = z.y * (skylike + miePhase * aerosol);
  transmittance = 1.0 - z.y * (1.0 - through);
}

// The luminance (cd/m^2) of the sunlight the clouds' shadows removed from the air between the camera
// and distance d (the alpha channels of tiles 0 and 1; 0 without cloud shadows). Two trilinear fetches.
float aerialPerspectiveShadowedLuminance(sampler3D volume, vec2 pixel, ivec2 image, float d, float maxDistance, float miePhase) {
  ivec3 size = textureSize(volume, 0);
  int columns = size.x / kAerialTiles;
  vec2 z = aerialDepthCoordinate(d, size.z, maxDistance);
  float y = aerialTileY(pixel.y, image.y, size.y);
  float skylike = textureLod(volume, vec3(aerialTileX(pixel.x, image.x, columns, 0), y, z.x), 0.0).a;
  float aerosol = textureLod(volume, vec3(aerialTileX(pixel.x, image.x, columns, 1), y, z.x), 0.0).a;
  return z.y * (skylike + miePhase * aerosol);
}

#endif  // FIRMAMENT_AERIAL_PERSPECTIVE_SAMPLING_GLSL
