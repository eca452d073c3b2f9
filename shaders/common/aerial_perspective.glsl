// aerial_perspective.glsl: the layout of the aerial-perspective volume (Hillaire 2020, section 5.4;
// sky/aerial_perspective_volume.h), shared by the pass that writes it
// (sky/aerial_perspective_volume.comp), the shaders that read it
// (atmosphere/aerial_perspective_sampling.glsl) and the C++ side (tests); compat.glsl rules.
//
// A volume of C x R froxel columns and N depth slices, for one camera and one spectral batch:
//  - column (i, j) follows the camera's own ray through the image point (i / (C - 1) * width,
//    j / (R - 1) * height) in pixel units (cameraRayDirection), so any projection works (perspective,
//    fisheye, equirectangular). The columns are corner-aligned: the first and last lie on the image's
//    edges, so every pixel interpolates between columns and none extrapolates (an equirectangular
//    image's left and right edges are the same direction, so its seam interpolates too). A fisheye's
//    columns outside its image circle take the direction on the circle's rim (pixels near the rim
//    interpolate towards it; no pixel outside the circle is drawn).
//  - slice k (0 .. N-1) holds the air from the camera to the distance d_k = D ((k + 1) / N)^2 along
//    the column's ray (quadratic: 78 m, 313 m, ... for D = 80 km and N = 32; the air near the camera
//    changes fastest). Before d_0 the value is interpolated from the camera's (no light, T = 1).
//  - the texture is RGBA, 3C x R x N, three tiles side by side: tile 0 (x < C) the in-scattered light
//    with the sky's spectrum (Rayleigh single scattering and all multiple scattering) in linear
//    Rec.709 cd/m^2, tile 1 the aerosols' single scattering of sunlight *without its phase function*
//    (converted with the sun's factors; the reader multiplies by p_M(nu) of its own pixel: nu is
//    constant along a ray, and the aerosol phase's forward peak (g = 0.8, ~10 degrees wide) is
//    narrower than what interpolation between columns a few degrees apart reproduces: with the phase
//    stored, the froxels' error peaked at 2 % around the sun), tile 2 the transmittance at the
//    batch's three wavelengths. Alpha of tiles 0 and 1: the luminance (cd/m^2) of the single scattering
//    that the clouds' shadows removed (light shafts, docs/clouds/README.md; tile 1's without the aerosol phase;
//    0 without cloud shadows); tile 2's alpha is 1. A lookup interpolates within a tile only
//    (corner alignment keeps the coordinate between the tile's first and last texel centres).
// Depth is the distance along the ray (not a view-space z), as the cloud march measures it.
#ifndef FIRMAMENT_AERIAL_PERSPECTIVE_GLSL
#define FIRMAMENT_AERIAL_PERSPECTIVE_GLSL

#include "common/camera.glsl"
#include "common/compat.glsl"

SHARED_BEGIN

// d_k in m: the far end of slice k of N over the maximum distance D.
SHARED_INLINE Real aerialSliceDepth(int k, int slices, Real maxDistance) {
  Real f = Real(k + 1) / Real(slices);
  return maxDistance * f * f;
}

// Image point (pixel units, (0, 0) the top-left corner of the image) of column (i, j) of C x R.
SHARED_INLINE vec2 aerialColumnPixel(int i, int j, int columns, int rows, int width, int height) {
  return vec2(Real(i) / Real(max(columns - 1, 1)) * Real(width), Real(j) / Real(max(rows - 1, 1)) * Real(height));
}

// The direction of a column through image point `pixel`: the camera's own mapping, with a fisheye's
// points outside its image circle (angle from the axis > pi) moved radially onto the rim.
SHARED_INLINE vec3 aerialColumnDirection(CameraParameters camera, vec2 pixel) {
  vec2 point = pixel;
  if (camera.projection == kProjectionFisheye) {
    vec2 plane = cameraImagePlane(camera, pixel);
    Real radius = length(plane);
    Real rim = 2.0 * kPi / max(camera.fov, 1e-6);  // theta = radius fov / 2 reaches pi here
    if (radius > rim) point = cameraPixelOfImagePlane(camera, plane * (rim / radius * (1.0 - 1e-6)));
  }
  bool valid;
  return cameraRayDirection(camera, point, valid);
}

const int kAerialTiles = 3;  // in-scattered sky-like light, aerosol single scattering / p_M, transmittance

// Texture x coordinate of image point `pixel` (pixel units) in tile 0, 1 or 2 of a volume of C columns.
SHARED_INLINE Real aerialTileX(Real pixelX, int width, int columns, int tile) {
  Real c = clamp(pixelX / Real(width), 0.0, 1.0) * Real(columns - 1);
  return (Real(tile * columns) + c + 0.5) / Real(kAerialTiles * columns);
}

// Texture y coordinate of image point `pixel` for R rows.
SHARED_INLINE Real aerialTileY(Real pixelY, int height, int rows) {
  return (clamp(pixelY / Real(height), 0.0, 1.0) * Real(rows - 1) + 0.5) / Real(rows);
}

// Depth lookup for distance d (m) in a volume of N >= 2 slices over D: x = the texture z coordinate,
// placed so that filtering between the two slices around d is linear in distance (not in slice
// index); y = the near factor f = min(d / d_0, 1). The air's value at d is then f * L(z) for the
// in-scattered light and 1 - f (1 - T(z)) for the transmittance (linear from the camera to d_0).
// Beyond D the last slice is returned.
SHARED_INLINE vec2 aerialDepthCoordinate(Real d, int slices, Real maxDistance) {
  Real n = Real(slices);
  Real distance = clamp(d, 0.0, maxDistance);
  Real w = clamp(n * sqrt(distance / maxDistance) - 1.0, 0.0, n - 1.0);  // slice index, fractional
  Real k = min(floor(w), n - 2.0);
  Real below = maxDistance * ((k + 1.0) / n) * ((k + 1.0) / n);
  Real above = maxDistance * ((k + 2.0) / n) * ((k + 2.0) / n);
  Real f = clamp((distance - below) / (above - below), 0.0, 1.0);
  Real near = clamp(distance / aerialSliceDepth(0, slices, maxDistance), 0.0, 1.0);
  return vec2((k + f + 0.5) / n, near);
}

SHARED_END

#endif  // FIRMAMENT_AERIAL_PERSPECTIVE_GLSL
