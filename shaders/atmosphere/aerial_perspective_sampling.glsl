// aerial_perspective_sampling.glsl (GPU only): reading the aerial-perspective volume
// (common/aerial_perspective.glsl has its layout; sky/aerial_perspective_volume.comp writes it): the
// air between the camera and distance d along the ray through image point `pixel`.
#ifndef FIRMAMENT_AERIAL_PERSPECTIVE_SAMPLING_GLSL
#define FIRMAMENT_AERIAL_PERSPECTIVE_SAMPLING_GLSL

#include "common/aerial_perspective.glsl"

// Where (pixel, d) lies in the volume: the texture coordinate of each of the three tiles and the blend
// towards the camera's values before the first slice (`near`: 0 at the camera, 1 from slice 0 on).
// pixel: image point in pixel units (a pixel's centre is its index + 0.5); image: width, height;
// maxDistance: the volume's D (m).
struct AerialCoordinates {
  vec3 tile[kAerialTiles];
  float near;
};
AerialCoordinates aerialCoordinates(sampler3D volume, vec2 pixel, ivec2 image, float d, float maxDistance) {
  ivec3 size = textureSize(volume, 0);
  int columns = size.x / kAerialTiles;
  vec2 z = aerialDepthCoordinate(d, size.z, maxDistance);
  float y = aerialTileY(pixel.y, image.y, size.y);
  AerialCoordinates c;
  for (int t = 0; t < kAerialTiles; ++t) c.tile[t] = vec3(aerialTileX(pixel.x, image.x, columns, t), y, z.x);
  c.near = z.y;
  return c;
}

// The air between the camera and distance d along the ray through image point `pixel` (volume: linear
// filtering, clamp to edge; miePhase: the aerosol phase function p_M(nu) of this pixel's ray, which
// the volume stores its light without). Out: the in-scattered light (linear Rec.709 cd/m^2, this
// batch's wavelengths) and the transmittance (this batch's three wavelengths). Three trilinear fetches.
void aerialPerspectiveLookup(sampler3D volume, vec2 pixel, ivec2 image, float d, float maxDistance, float miePhase,
                             out vec3 light, out vec3 transmittance) {
  AerialCoordinates c = aerialCoordinates(volume, pixel, image, d, maxDistance);
  vec3 skylike = textureLod(volume, c.tile[0], 0.0).rgb;
  vec3 aerosol = textureLod(volume, c.tile[1], 0.0).rgb;
  vec3 through = textureLod(volume, c.tile[2], 0.0).rgb;
  light = c.near * (skylike + miePhase * aerosol);
  transmittance = 1.0 - c.near * (1.0 - through);
}

// The luminance (cd/m^2) of the sunlight the clouds' shadows removed from the air between the camera
// and distance d (the alpha channels of tiles 0 and 1; 0 without cloud shadows). Two trilinear fetches.
float aerialPerspectiveShadowedLuminance(sampler3D volume, vec2 pixel, ivec2 image, float d, float maxDistance, float miePhase) {
  AerialCoordinates c = aerialCoordinates(volume, pixel, image, d, maxDistance);
  return c.near * (textureLod(volume, c.tile[0], 0.0).a + miePhase * textureLod(volume, c.tile[1], 0.0).a);
}

#endif  // FIRMAMENT_AERIAL_PERSPECTIVE_SAMPLING_GLSL
