#pragma once
// The CPU reference of the ground's luminance (docs/terrain.md, "Reference of the ground's light"): the
// light a Lambertian terrain reflects towards the camera, at the surface (no air between camera and
// ground: the GPU pass's TerrainPassOptions::groundOnly output is what it is compared with), computed
// without the fast path's approximations, in double, over the same height field, normals and albedo:
//   L = albedo [ (1/pi) E_sun(p) <V(s) e^-tau(s) max(n.s, 0)>_disc + <L_in(w)>_cos ],
// - the sun: E_sun through the atmosphere at p by the shared optical depth to the top (no table,
//   CloudPathTracer::sunIrradianceAt), averaged over the sun's disc (radius 0.265 deg, sunDiscSamples
//   directions): V the terrain's visibility (the CPU pyramid walk of terrain/terrain_intersection.h),
//   tau the clouds' optical depth by a fine march of the path tracer's extinction (CloudMedium, the
//   same medium as the GPU march: common/cloud_density.glsl on the read-back noise), so soft shadow
//   edges (penumbrae) are in the reference;
// - the light from the hemisphere over the normal, cosine-weighted (skyDirections per pixel,
//   stratified): a direction that meets the terrain brings nothing (no ground-to-ground bounce, as the
//   fast path), any other brings the clear sky's radiance (the atmosphere's CPU reference,
//   atmosphere/reference_renderer.h, tabulated over the upper hemisphere at two heights) times the
//   clouds' transmittance along it, plus the light the clouds scatter into it (the cloud path tracer,
//   clouds/reference_clouds.h, one path per direction: sunlight and sky light through every scattering
//   order). So the reference holds the terrain's occlusion of the sky, the clouds' dimming and their
//   own light, and the sky's anisotropy.
// Radiance is carried at the fast path's three wavelengths and converted to Rec.709 with the same
// matrices; the albedo (linear Rec.709) multiplies after the conversion, as on the GPU.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "clouds/reference_clouds.h"
#include "core/image.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "sky/scene_view.h"
#include "terrain/scene_terrain.h"

namespace firmament {

struct TerrainReferenceSettings {
  int skyDirections = 64;  // cosine-weighted hemisphere directions per pixel
  int sunDiscSamples = 8;  // directions over the sun's disc per pixel (per sub-pixel)
  // pixelSide × pixelSide view rays per pixel at the centres of equal sub-pixels, each with its own hit,
  // the sun's disc and skyDirections / pixelSide² of the hemisphere: the pixel's area, which a renderer
  // that filters the terrain (its level of detail) renders. 1: the pixel's centre.
  int pixelSide = 1;
  int skyTableZenith = 12;    // clear-sky radiance table: zenith bands over the upper hemisphere
  int skyTableSamples = 8;    // the atmosphere reference's paths per table direction
  double cloudStep_m = 10.0;  // the march of the clouds' optical depth along the sun's rays
  uint64_t seed = 1;
  int threads = 0;  // 0: all cores
};

struct TerrainReferencePixel {
  bool hit = false;
  double luminance = 0.0;      // cd/m^2 of the ground at the surface
  double standardError = 0.0;  // of the luminance (the hemisphere's Monte Carlo)
  double sunLuminance = 0.0;   // the sun's part
  double sunVisibility = 0.0;  // <V e^-tau>_disc: 1 lit, 0 in full shadow
  double skyLuminance = 0.0;   // the hemisphere's part
  double skyOcclusion = 0.0;   // share of the cosine-weighted hemisphere the terrain hides
  double t = 0.0;              // distance to the hit along the view ray (m; the nearest sub-pixel's)
};

struct TerrainReferenceImage {
  int width = 0, height = 0;
  std::vector<TerrainReferencePixel> pixels;
  double seconds = 0.0;
};

// The reference of `scene` (with a /terrain section) as seen by `view` (sky/scene_view.h, the camera
// on the terrain as SkyRenderer places it: view.cameraRadius). medium: the scene's clouds
// (sky/scene_cloud_medium.h; an empty medium without clouds); lighting: the clouds' phase and albedo.
TerrainReferenceImage renderTerrainReference(const Scene& scene, const SceneView& view,
                                             const terrain::ResolvedTerrain& terrain, const CloudMedium& medium,
                                             const CloudLightingSettings& lighting,
                                             const TerrainReferenceSettings& settings);

// A fast-path ground image (TerrainPassOptions::groundOnly: rgb cd/m^2) against the reference, over the
// pixels both see terrain at (the GPU's depth below 1e29 and the reference's hit, their distances
// within 1 %: silhouettes where the float cast and the double walk disagree are left out).
// relRmse = sqrt(sum (a - Y)^2 / sum Y^2), noiseCorrected as clouds/reference_clouds.h's
// compareWithCloudReference (the reference's own noise removed), meanBias = mean(a) / mean(Y) - 1,
// shadowBias / litBias the same over the pixels whose reference sun visibility is below 0.5 / above.
struct TerrainReferenceError {
  double relRmse = 0.0, noiseFloor = 0.0, noiseCorrected = 0.0, meanBias = 0.0;
  double shadowBias = 0.0, litBias = 0.0;
  double meanTest = 0.0, meanReference = 0.0;
  int pixels = 0, shadowPixels = 0;
};
TerrainReferenceError compareWithTerrainReference(const Image& groundOnly, const std::vector<float>& depth,
                                                  const TerrainReferenceImage& reference);

// The clouds' optical depth (550 nm; grey) along the ray from p towards `direction`, marched through
// the layers' shells in steps of at most step_m (midpoint rule).
double cloudOpticalDepthAlong(const CloudMedium& medium, glm::dvec3 p, glm::dvec3 direction, double step_m);

}  // namespace firmament
