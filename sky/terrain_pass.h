#pragma once
// The terrain in the frame (docs/terrain.md): the scene's height field ray-cast on the GPU from the
// camera (shaders/terrain/cast_terrain.comp: the min/max pyramid walk of terrain/terrain_intersection.h
// in float, a shadow ray at the sun, the clouds' optical depth along the sun line from their Beer shadow
// map), then shaded once per spectral batch (shaders/terrain/shade_terrain.comp: a Lambertian ground
// under sun and sky light through the air and the clouds, the air between camera and ground) over the
// frame's pixels that meet it. It leaves, per pixel, the distance to the terrain that the cloud march
// stops at. Created only for scenes with a /terrain section.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/atmosphere_luts.h"
#include "clouds/cloud_settings.h"
#include "common/camera.glsl"
#include "core/scene.h"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/dispatch.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "terrain/horizon_map.h"
#include "terrain/scene_terrain.h"

namespace firmament {

// How the ground's sky light is modelled (shaders/terrain/shade_terrain.comp; docs/terrain.md, "Shading").
enum class TerrainSkyLight {
  Deck,  // the clear-sky table dimmed by the clouds' Eddington deck transmission, plus the sun's diffuse part,
         // for the slab of the point's own cloud column (an infinite deck)
  DeckHemisphere,  // the same averaged over the cloud cover the point's hemisphere sees (8 directions to
                   // the clouds' middle height, each column's optical depth from the shadow map)
  Clear,           // the clear-sky table alone: no dimming under cloud, no diffuse sunlight through it
};

// How the sky light excludes the sky the terrain hides (shaders/terrain/cast_terrain.comp; docs/terrain.md,
// "Sky light the terrain hides"; decision 0205).
enum class TerrainSkyOcclusion {
  None,        // (1 + n.z) / 2: an isotropic sky over a tilted plane, nothing hidden
  HorizonMap,  // the horizons of a map baked once per terrain (terrain/horizon_map.h), sliced per pixel
  Rays,        // occlusionRays rays per pixel, cosine-weighted, cast in the height field
};

// Knobs of the terrain pass that a bench or a test sets (SkyRenderOptions::terrain).
struct TerrainPassOptions {
  bool selfShadow = true;  // a shadow ray per pixel at the sun
  // Soft cloud-shadow edges from the sun's disc: the shadow map read over the disc's footprint
  // (shaders/terrain/cast_terrain.comp); off: one lookup at the sun's centre.
  bool penumbra = true;
  TerrainSkyLight skyLight = TerrainSkyLight::DeckHemisphere;
  TerrainSkyOcclusion skyOcclusion = TerrainSkyOcclusion::HorizonMap;
  int horizonAzimuths = 16;  // the horizon map's azimuths
  int occlusionRays = 16;    // rays per pixel for TerrainSkyOcclusion::Rays
  // Level of detail by distance (terrain/terrain_lod.h, docs/terrain.md "Level of detail"): the surface is
  // the field filtered to cells of lodFootprint × the pixel's cone width (distance × pixel angle) wherever
  // that exceeds the field's cell; 0: the field's own samples at every distance (point sampling). 0.7:
  // the least error against 4 × 4 sub-pixels and their own frame-to-frame change in a pan (decision 0206).
  double lodFootprint = 0.7;
  // The ground's own radiance at the surface, without the air between camera and ground (eval's ground
  // reference compares this); the sky's pixels stay.
  bool groundOnly = false;
};

struct TerrainPassView {
  glm::dvec3 cameraPosition{0.0};          // planet-centred (the camera on +z of its ground point's ENU frame)
  glm::dvec3 sunDirection{0.0, 0.0, 1.0};  // the light's direction (the Sun's, or the Moon's at night)
  shared::CameraParameters camera{};
  // Per spectral batch, the atmosphere block whose conversions carry the light (sky/frame_light.h);
  // empty: each batch's own block, the Sun.
  std::vector<const gpu::Buffer*> lightBlocks;
  int airSteps = 32;       // the air march's steps to the ground (the sky's view steps)
  bool selfShadow = true;  // a shadow ray per pixel at the sun
  TerrainSkyLight skyLight = TerrainSkyLight::Deck;
  TerrainSkyOcclusion skyOcclusion = TerrainSkyOcclusion::None;
  int horizonAzimuths = 16;
  int occlusionRays = 16;
  bool groundOnly = false;    // TerrainPassOptions::groundOnly
  double lodFootprint = 0.0;  // TerrainPassOptions::lodFootprint
  // The sun's angular radius (rad) for the cloud shadows' penumbrae; 0: no penumbra.
  double sunAngularRadius = 0.0;
  // The clouds' middle radius (m; the mean of the layers' middles): where TerrainSkyLight::DeckHemisphere
  // reads the cover; 0 without clouds.
  double cloudMiddleRadius = 0.0;
  // The mean cosine of the clouds' phase function, for the deck's diffuse transmission (Eddington's
  // (1 - g) tau): cloudPhaseMeanCosine of the scene's lighting.
  double deckAsymmetry = 0.85;
};

// The mean cosine of the clouds' two-lobe phase (clouds/cloud_settings.h CloudLightingSettings):
// (1 - w) g_F + w <cos>_Draine(g_B, alpha), with Draine's <cos> = g (1 + alpha (3 + 2 g^2) / 5) /
// (1 + alpha (1 + 2 g^2) / 3) (Draine 2003, ApJ 598, 1017; HG's g for alpha = 0). The default dual HG
// (0.8, -0.3, w 0.3): 0.47.
double cloudPhaseMeanCosine(const CloudLightingSettings& lighting);

// The angle (rad) one pixel spans at the image's centre: 2 tan(fov / 2) / width for a perspective
// camera, fov / width for the equidistant fisheye, 2 pi / width for the equirectangular.
double cameraPixelAngle(const shared::CameraParameters& camera);

// The clouds' Beer shadow map and where it lies (clouds/cloud_pass.h ShadowPlacement).
struct TerrainCloudShadow {
  const gpu::Image* map = nullptr;
  glm::dvec3 centre{0.0}, u{1.0, 0.0, 0.0}, v{0.0, 1.0, 0.0};
  double extent_m = 1.0, start_m = 0.0;
};

class TerrainPass {
 public:
  explicit TerrainPass(gpu::Context& context);

  // Resolves the scene's terrain (terrain/scene_terrain.h) and uploads the heights and the pyramid;
  // kept while the scene's /terrain and /location and the radius are unchanged. True when resolved now.
  bool prepare(const Scene& scene, double planetRadius);
  const terrain::ResolvedTerrain& resolved() const { return *resolved_; }
  // The ground height under the camera (m above sea level): the field at the location.
  double groundUnderCamera() const;
  // Seconds the last resolution took (0 when reused).
  double resolveSeconds() const { return resolveSeconds_; }
  // The horizon map of the resolved terrain with `azimuths` directions (terrain/horizon_map.h), baked on
  // the CPU and uploaded by the first call (or record() with TerrainSkyOcclusion::HorizonMap), kept
  // with the terrain. horizonSeconds(): the last bake's time (0 when reused).
  const terrain::HorizonMap& horizonMap(int azimuths);
  double horizonSeconds() const { return horizonSeconds_; }

  // Records the cast (a barrier after) and the shading of each spectral batch into `frame` (RGBA32F,
  // the view's pixels, row-major; the sky written before, a barrier between). skyIrradiance[b]: batch b's
  // ground irradiance table. shadow: the clouds' Beer shadow map (baked before, a barrier between), or
  // null. A barrier follows the last shading.
  void record(const TerrainPassView& view, const AtmosphereLuts& luts,
              const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& frame, const gpu::TileDispatch& tiles,
              gpu::CommandList& commands, const TerrainCloudShadow* shadow = nullptr);

  // Per pixel of the last record(): the distance to the terrain along the view ray (m; 1e30 where it
  // meets none). Valid once the recorded commands ran.
  const gpu::Buffer& depth() const { return depth_; }
  // Per pixel three vec4: (normal, t), (sun visibility past the terrain, cloud optical depth to the sun,
  // height, sky share), (deck's diffuse sunlight, deck's transmission of sky light, 0, 0)
  // (shaders/terrain/cast_terrain.comp).
  const gpu::Buffer& hits() const { return hits_; }

  // Records the cast alone (the pixels' hits and depth: hits(), depth()) and a barrier; record() runs it
  // before the shading. For tests: a shadow map made by hand.
  void recordCast(const TerrainPassView& view, const gpu::TileDispatch& tiles, gpu::CommandList& commands,
                  const TerrainCloudShadow* shadow = nullptr);

  // The GPU cast on given rays, for tests: per ray (origin, r) and (direction, mu) in; per ray
  // (normal, t) and (height, surface, 0, 0) out. Submits and waits.
  std::vector<glm::vec4> castRays(const std::vector<glm::vec4>& rays);

 private:
  void uploadBlock(const TerrainPassView& view, const TerrainCloudShadow* shadow);

  gpu::Context& context_;
  gpu::ComputePipeline cast_;
  gpu::ComputePipeline shade_;
  std::unique_ptr<gpu::ComputePipeline> castRays_;  // created by the first castRays()
  std::unique_ptr<terrain::ResolvedTerrain> resolved_;
  std::string key_;
  double planetRadius_ = 0.0;
  double resolveSeconds_ = 0.0;
  double horizonSeconds_ = 0.0;
  std::unique_ptr<terrain::HorizonMap> horizon_;  // of the resolved terrain
  gpu::Buffer horizonBuffer_;
  // Per pyramid level: offset of its group of LOD bounds, width, height, offset of the LOD level's heights.
  std::vector<glm::ivec4> levels_;
  int lodLevels_ = 0;  // the highest LOD level (terrain/terrain_lod.h)
  float fieldTop_ = 0.0f;
  gpu::Buffer block_;
  gpu::Buffer heights_;
  gpu::Buffer pyramid_;
  gpu::Buffer hits_;
  gpu::Buffer depth_;
  gpu::Image shadowPlaceholder_;
  gpu::Sampler linearClamp_;
};

}  // namespace firmament
