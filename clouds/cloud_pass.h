#pragma once
// The cloud ray-march pass (shaders/clouds/render_clouds.comp): cloud layers lit by the sun through the
// atmosphere's transmittance table and by the sky irradiance table, composited over a rendered sky
// image in place (docs/clouds.md). One dispatch per spectral batch of the atmosphere tables.
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/atmosphere_luts.h"
#include "clouds/cloud_noise.h"
#include "clouds/cloud_settings.h"
#include "clouds/cloud_weather_map.h"
#include "common/camera.glsl"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/dispatch.h"

namespace firmament {

struct CloudView {
  glm::dvec3 cameraPosition{0.0};          // planet-centred, m (the camera on +z of its ground point's ENU frame)
  glm::dvec3 sunDirection{0.0, 0.0, 1.0};  // the light's direction (the Sun's, or the Moon's at night)
  shared::CameraParameters camera{};
  // Per spectral batch of the tables, the atmosphere block whose Rec.709 conversions carry the light's
  // spectrum and irradiance (the tables are linear in the light: sky/frame_light.h); empty: each batch's
  // own block, the Sun.
  std::vector<const gpu::Buffer*> lightBlocks;
};

// Density evaluations per pixel of the last recorded march (after its commands ran).
struct CloudSampleCounts {
  double viewPerPixel = 0.0;   // view march: coarse (shape-only) and fine samples
  double lightPerPixel = 0.0;  // light march samples
  // The per-frame maps' bakes (the other layers' map, the column map): a fixed cost per frame whatever
  // the image size, which they save many times over in the light march at useful sizes.
  double mapPerPixel = 0.0;
};

// The aerial-perspective volume that the march reads with AerialPerspective::Volume: one image per
// spectral batch of the atmosphere tables (layout: shaders/common/aerial_perspective.glsl; written by
// sky/aerial_perspective_volume.h) and the distance D its slices reach.
struct CloudAerialVolume {
  std::vector<const gpu::Image*> volumes;
  double maxDistance_m = 0.0;
};

// The march's specialization constant kMarchFeatures (shaders/clouds/render_clouds.glsl): a bit per
// option whose code the frame needs: 1 light through other layers (more than one layer), 2 the Beer
// shadow map, 4 the weather map's coverage reach (weatherReach), 8 free (removed: decision 0002), 16 the
// light cone, 32 more than one layer, 64 the other layers' light from their map, 128 by marching their
// crossings (one of the two with bit 1), 256 the vertical optical depths from the column map, 512 by
// marching up and down (one of the two), 1024 the own layer's far light from the deep shadow map, 2048
// the reflected light (a layer's ms_r > 0), 4096 its way behind a sample by marching (with 2048, where
// the deep shadow map may not hold it: without the map, with the Beer shadow map, or unless
// sunClearsEverySample). All bits with march.specializeMarch off.
uint32_t cloudMarchFeatures(const CloudSettings& settings, bool weatherReach, bool sunClearsEverySample);

// Whether the sun stands above the horizon of every point the view march can reach (within
// march.maxDistance_m of the camera), with a margin: then every lit sample's sun ray climbs, and the deep
// shadow map holds its way to the top and behind it.
bool sunClearsEveryCloudSample(const CloudMarchSettings& march, const CloudView& view);

class CloudPass {
 public:
  explicit CloudPass(gpu::Context& context);

  // Records the noise bake into `commands` when the seed or sizes changed; true when it did.
  bool prepareNoise(const CloudSettings& settings, const CloudNoiseSettings& noise, gpu::CommandList& commands);

  // The weather map the march reads (uploaded now; kept until the next call). Must be set before
  // record().
  void setWeatherMap(const CloudWeatherMap& map);

  // Records the Beer shadow map's bake (when settings.march.beerShadowMap; nothing otherwise) ahead of
  // record(), for passes that read the map before the march (the aerial-perspective volume's light
  // shafts); record() then does not bake again. Same arguments as record(); aerialDistance_m: the
  // aerial-perspective volume's depth D (0 without one). A barrier follows the bake.
  void recordShadowMap(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                       const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                       double aerialDistance_m, gpu::CommandList& commands);

  // Where the Beer shadow map lies (common/cloud_shadow.glsl), as of the last recordShadowMap() or record().
  struct ShadowPlacement {
    glm::dvec3 centre{0.0}, u{1.0, 0.0, 0.0}, v{0.0, 1.0, 0.0};
    double extent_m = 1.0, start_m = 0.0;
  };
  const ShadowPlacement& shadowPlacement() const { return shadowPlacement_; }

  // Records the march over `skyFrame` (RGBA32F pixels of the view, row-major), one dispatch per batch of `luts`
  // with skyIrradiance[b] the batch's sky irradiance table. The noise must be prepared and baked
  // (a barrier between) and the sky written before (a barrier between). With
  // settings.march.aerialPerspective == Volume, `aerial` is the volume of this view, written before (a
  // barrier between); otherwise it is not read (may be null).
  //
  // continueSequence: this frame follows the previous record() in a sequence, so with
  // settings.march.temporalUpdate N > 1 it may march 1 in N pixels and reproject the rest from the
  // previous frame (clouds/temporal_resolve). It does so only when the previous frame was recorded
  // with the same cloud settings, image size and weather map, and the camera is not inside a layer;
  // otherwise every pixel is marched (and the next frame can reproject from this one).
  //
  // terrainDepth: per image pixel the distance to the terrain (m; sky/terrain_pass.h), where the march
  // stops; null without terrain (the march's code for it is compiled out).
  void record(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
              const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
              const gpu::TileDispatch& tiles, gpu::CommandList& commands, const CloudAerialVolume* aerial = nullptr,
              bool continueSequence = false, const gpu::Buffer* terrainDepth = nullptr);

  // RGBA32F pixels of the view, row-major: rgb = the clouds' light in front of the sky (cd/m^2, aerial
  // perspective included), a = the clouds' transmittance. Valid after the recorded commands ran.
  const gpu::Buffer& cloudFrame() const { return cloudFrames_[current_]; }
  // Whether the last record() reprojected (marched 1 in temporalUpdate pixels).
  bool lastFrameReprojected() const { return reprojected_; }
  // The Beer shadow map of the last record() with it enabled (RGBA32F: front depth m, mean extinction
  // 1/m, total optical depth, 0; common/cloud_shadow.glsl).
  const gpu::Image& shadowMap() const { return shadowImage_; }
  CloudNoise& noise() { return noise_; }
  CloudSampleCounts sampleCounts() const;

 private:
  // Fills and uploads the cloud block; returns the history's key (the block without camera, sun and wind).
  std::vector<uint8_t> uploadBlock(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                                   double aerialDistance_m);
  void allocateShadowImage(const CloudMarchSettings& march);
  // Bakes the other layers' map when the frame uses it (clouds/other_layer_map.glsl; a 1x1 placeholder
  // otherwise), a barrier after.
  void recordOtherLayerMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                           const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                           gpu::CommandList& commands);
  // Bakes the column map when the frame uses it (clouds/column_map.glsl; a placeholder otherwise), a
  // barrier after.
  void recordColumnMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                       const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                       gpu::CommandList& commands);
  // Bakes the deep shadow map when the frame uses it (clouds/deep_shadow_map.glsl; a placeholder
  // otherwise), a barrier after.
  void recordDeepShadowMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                           const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                           gpu::CommandList& commands);
  // Bakes a map of K + 1 levels per layer (the column map, the deep shadow map: 3D R32F, size x size x
  // layers (K + 1); a 1x1x2 placeholder into `image` while off) on this frame's rows, a barrier after.
  // extraSlices: slices after the layers' levels that the bake does not write (the column map's ambient).
  void recordLevelMap(gpu::ComputePipeline& pipeline, gpu::Image& image, bool bake, int size, int levels, size_t layers,
                      int extraSlices, const char* name, const char* pass, const AtmosphereLuts& luts,
                      const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                      gpu::CommandList& commands);
  // A frame's temporal plan (cloud_temporal.cpp): the block side k (1: every pixel marched), the wind's
  // offset, and whether the weather map is the history's or evolved from it by little.
  struct TemporalPlan {
    int k = 1;
    glm::dvec3 windOffset{0.0};
    bool sameWeather = false;
  };
  // Decides k and whether this frame reprojects (sets reprojected_): the same settings and weather, the
  // camera outside the layers, a sequence continued at full resolution.
  TemporalPlan planTemporal(const CloudMarchSettings& march, const CloudView& view,
                            const std::vector<shared::CloudLayer>& layers, const std::vector<uint8_t>& settingsKey,
                            bool continueSequence);
  // The pixel (x, y) of each k x k block this reprojected frame marches (the Bayer order over k^2 frames).
  void blockPixel(int k, int offset[2]) const;
  // The reprojection: the fresh neighbourhoods on the march's grid, then the image from the history.
  void recordTemporalResolve(const CloudView& view, const CloudMarchSettings& march, const TemporalPlan& plan,
                             uint32_t coarseWidth, uint32_t coarseHeight, const gpu::TileDispatch& marchTiles,
                             const gpu::TileDispatch& tiles, const int offset[2], gpu::Buffer& cloudFrame,
                             const gpu::Buffer& historyFrame, gpu::Buffer& skyFrame, gpu::CommandList& commands);
  // Keeps what the next frame's reprojection compares with.
  void rememberHistory(std::vector<uint8_t> settingsKey, const CloudView& view, const TemporalPlan& plan);
  // Places the per-frame maps (cloud_maps.cpp): one in w of their rows when the frame continues one that
  // baked them and little moved, else all rows at this frame's camera and sun; re-uploads the block.
  void placeMaps(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                 const std::vector<uint8_t>& settingsKey, const TemporalPlan& plan, bool continueSequence,
                 double aerialDistance_m);
  // The rows of a map `height` rows high that this frame bakes: every rowStride-th from firstRow.
  uint32_t bakedRows(uint32_t height) const {
    return (height - uint32_t(maps_.firstRow) + uint32_t(maps_.rowStride) - 1) / uint32_t(maps_.rowStride);
  }
  // Binds a bake (cloudBakeDesc in cloud_pass.cpp; cloud_maps.cpp): the march's first 13 bindings (the frames bound,
  // unread) and `target`, the image it writes.
  void bindBake(gpu::ComputePipeline& pipeline, const gpu::Image& target, const AtmosphereLuts& luts,
                const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame, gpu::CommandList& commands);
  void recordBake(const AtmosphereLuts& luts, const std::vector<const gpu::Image*>& skyIrradiance,
                  gpu::Buffer& skyFrame, gpu::CommandList& commands);

  // The block of batch b for the light of the view being recorded (CloudView::lightBlocks).
  const gpu::Buffer& lightBlock(const AtmosphereLuts& luts, size_t b) const {
    return b < lightBlocks_.size() ? *lightBlocks_[b] : luts.batch(b).block;
  }

  gpu::Context& context_;
  std::vector<const gpu::Buffer*> lightBlocks_;  // the view's, set by record() and recordShadowMap()
  CloudNoise noise_;
  // clouds/render_clouds (volume), render_clouds_ap_march, render_clouds_ap_off, each specialized for
  // the options a frame uses (cloudMarchFeatures): created on first use, keyed by AerialPerspective and
  // the features.
  std::map<std::pair<int, uint32_t>, std::unique_ptr<gpu::ComputePipeline>> pipelines_;
  gpu::Image aerialPlaceholder_;         // 2x2x2, bound where the variant reads no volume
  gpu::Buffer terrainDepthPlaceholder_;  // one float (1e30), bound without terrain
  gpu::ComputePipeline bakeShadow_;
  gpu::ComputePipeline bakeOtherLayers_;    // clouds/bake_other_layers
  gpu::ComputePipeline bakeColumns_;        // clouds/bake_columns
  gpu::ComputePipeline bakeColumnAmbient_;  // clouds/bake_column_ambient
  gpu::ComputePipeline bakeDeepShadow_;     // clouds/bake_deep_shadow
  gpu::ComputePipeline upsample_;           // clouds/upsample_clouds (reduced-resolution march)
  gpu::ComputePipeline neighbourhood_;      // clouds/temporal_neighbourhood (temporal reprojection, step 1)
  gpu::ComputePipeline resolve_;            // clouds/temporal_resolve (step 2)
  gpu::Image shadowImage_;                  // Beer shadow map (1x1 placeholder while off)
  gpu::Image otherLayerImage_;              // the other layers' map (1x1 placeholder while off)
  gpu::Image columnImage_;                  // the column map (1x1x2 placeholder while off)
  gpu::Image deepShadowImage_;              // the deep shadow map (1x1x2 placeholder while off)
  gpu::Buffer block_;
  gpu::Buffer counters_;
  gpu::Image weatherImage_;
  gpu::Image weatherReach_;   // coverageReach of a sharp map (1x1 otherwise), R32F, linear, repeat
  double reachRadius_ = 0.0;  // m; 0: the map is smooth, the margin test applies
  static constexpr double kReachRadius_m = 2000.0;
  glm::dvec4 weatherRegion_{0.0};  // width, height (m), skew east, north (m/m)
  // This frame's and the previous frame's cloud frames (the history), swapped by every record().
  gpu::Buffer cloudFrames_[2];
  int current_ = 0;
  gpu::Buffer coarseFrame_;  // the march's frame at reduced resolution
  gpu::Buffer depth_;        // the march's depth per pixel of its grid (common to all grids: w x h floats)
  gpu::Buffer temporalBlock_;
  gpu::Buffer neighbourhoodRecords_;  // 3 vec4 per grid pixel (clouds/temporal_neighbourhood.comp)
  size_t cloudPixels_ = 0;
  // What the previous frame was, for reprojection.
  struct History {
    bool usable = false;            // recorded with temporal update > 1
    std::vector<uint8_t> settings;  // the cloud block without camera, sun and wind (clouds/cloud_block.cpp)
    uint64_t weather = 0;
    glm::dvec4 weatherRegion{0.0};
    std::vector<float> weatherTexels;  // the map's texels, to tell a map that has evolved a little
    CloudView view;
    glm::dvec3 windOffset{0.0};
  } history_;
  uint64_t weatherHash_ = 0;
  std::vector<float> weatherTexels_;
  uint32_t temporalFrame_ = 0;  // counts reprojected frames: picks each block's pixel and the noise shift
  bool reprojected_ = false;
  // The per-frame maps' placements (the other layers' map, clouds/other_layer_map.glsl, and the deep
  // shadow map, clouds/deep_shadow_map.glsl, on one plane; the column map, clouds/column_map.glsl) and
  // the rows the coming bakes write (the same for all).
  struct MapPlacement {
    bool baked = false;  // the last record() baked them (all or some rows)
    glm::dvec3 origin{0.0}, u{1.0, 0.0, 0.0}, v{0.0, 1.0, 0.0}, sun{0.0, 0.0, 1.0};
    glm::dvec3 column{0.0, 0.0, 1.0}, columnU{1.0, 0.0, 0.0}, columnV{0.0, 1.0, 0.0};
    int firstRow = 0, rowStride = 1;
  } maps_;
  bool shadowBaked_ = false;  // recordShadowMap() ran for the coming record()
  ShadowPlacement shadowPlacement_;
};

}  // namespace firmament
