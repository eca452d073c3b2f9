#include "sky/terrain_pass.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/cloud_lighting.glsl"
#include "core/error.h"
#include "terrain/min_max_pyramid.h"
#include "terrain/terrain_lod.h"

namespace firmament {
namespace {

constexpr int kMaxLevels = 16;  // kTerrainMaxLevels in shaders/terrain/terrain_block.glsl
// The highest LOD level: cells 256 times the field's (decision 0206).
constexpr int kMaxLodLevel = 8;

// std140 mirror of TerrainBlock in shaders/terrain/terrain_block.glsl.
struct TerrainBlock {
  float cameraPosition[4];
  float cameraForward[4];
  float cameraRight[4];
  float cameraUp[4];
  float sunDirection[4];
  int32_t image[4];
  float grid[4];
  int32_t gridSize[4];
  float heights[4];
  float shadowCentre[4];
  float shadowU[4];
  float shadowV[4];
  float albedoRock[4];
  float albedoVegetation[4];
  float albedoSnow[4];
  float albedoLines[4];
  float albedoSlopes[4];
  int32_t skyOcclusion[4];
  int32_t horizonSize[4];
  float horizonGrid[4];
  float deck[4];
  float lod[4];
  int32_t levels[kMaxLevels][4];
};
static_assert(sizeof(TerrainBlock) == (22 + kMaxLevels) * 16);

void put(float (&out)[4], const glm::dvec3& v, double w = 0.0) {
  out[0] = float(v.x);
  out[1] = float(v.y);
  out[2] = float(v.z);
  out[3] = float(w);
}

struct TilePush {
  gpu::TileDispatch tiles;
};

struct ShadePush {
  gpu::TileDispatch tiles;
  int32_t accumulate;
  int32_t last;
  int32_t groundOnly;
  int32_t pad;
};

}  // namespace

double cloudPhaseMeanCosine(const CloudLightingSettings& l) {
  return shared::cloudPhaseMeanCosine(l.gForward, l.gBack, l.backWeight, l.alpha);
}

double cameraPixelAngle(const shared::CameraParameters& camera) {
  const double width = std::max(camera.width, 1);
  if (camera.projection == shared::kProjectionEquirectangular) return 2.0 * shared::kPi / width;
  if (camera.projection == shared::kProjectionFisheye) return camera.fov / width;
  return 2.0 * std::tan(0.5 * camera.fov) / width;
}

TerrainPass::TerrainPass(gpu::Context& context)
    : context_(context),
      cast_(context,
            {"terrain/cast_terrain",
             {gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
              gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::SampledImage,
              gpu::BindingType::StorageBuffer},
             sizeof(TilePush)}),
      shade_(context,
             {"terrain/shade_terrain",
              {gpu::BindingType::UniformBuffer, gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer,
               gpu::BindingType::StorageBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
               gpu::BindingType::SampledImage, gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer,
               gpu::BindingType::StorageBuffer},
              sizeof(ShadePush)}),
      block_(context, sizeof(TerrainBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host, "terrain block"),
      shadowPlaceholder_(context, {1, 1, 1, gpu::Format::RGBA32F, false, true, "terrain cloud shadow placeholder"}),
      linearClamp_(context, gpu::Filter::Linear, gpu::AddressMode::Clamp) {
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  shadowPlaceholder_.upload(zero, sizeof(zero));
  horizonBuffer_ = gpu::Buffer(context_, sizeof(zero), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device,
                               "terrain horizon placeholder");
  horizonBuffer_.upload(zero, sizeof(zero));
}

const terrain::HorizonMap& TerrainPass::horizonMap(int azimuths) {
  if (!resolved_) throw std::logic_error("TerrainPass: prepare before horizonMap");
  horizonSeconds_ = 0.0;
  if (horizon_ && horizon_->azimuths == azimuths) return *horizon_;
  terrain::HorizonMapSettings settings;
  settings.azimuths = std::clamp(azimuths, 1, 64);
  horizon_ = std::make_unique<terrain::HorizonMap>(terrain::bakeHorizonMap(resolved_->field, planetRadius_, settings));
  horizonBuffer_ = gpu::Buffer(context_, horizon_->elevation.size() * sizeof(float), gpu::BufferUsage::Storage,
                               gpu::MemoryLocation::Device, "terrain horizon map");
  horizonBuffer_.upload(horizon_->elevation);
  horizonSeconds_ = horizon_->seconds;
  return *horizon_;
}

bool TerrainPass::prepare(const Scene& scene, double planetRadius) {
  const terrain::TerrainSettings settings = terrain::terrainSettingsFromScene(scene);
  char radius[64];
  std::snprintf(radius, sizeof(radius), "|%a|", planetRadius);
  const std::string key =
      scene.at("/terrain").dump() + "|" + scene.at("/location").dump() + radius + settings.file.string();
  resolveSeconds_ = 0.0;
  if (resolved_ && key == key_) return false;
  auto resolved = std::make_unique<terrain::ResolvedTerrain>(terrain::resolveSceneTerrain(scene, planetRadius));
  const terrain::HeightField& field = resolved->field;
  if (field.nx < 2 || field.ny < 2) throw InputError("terrain: the height field needs at least 2 x 2 samples");
  const terrain::TerrainLod lod = terrain::buildTerrainLod(field, kMaxLodLevel);
  const terrain::MinMaxPyramid& pyramid = lod.levelBounds[0];
  if (pyramid.levels() > kMaxLevels)
    throw InputError("terrain: resolution " + std::to_string(std::max(field.nx, field.ny)) +
                     " needs more than 16 pyramid levels; allowed: up to 32769 samples a side");
  lodLevels_ = int(lod.levels.size()) - 1;
  // Pyramid level L's group: the bounds of LOD levels k = 0 ... min(L, lodLevels_) over its nodes
  // (terrain_block.glsl terrainLodNodeRange); the heights, then LOD levels 1 ... lodLevels_'s samples.
  std::vector<float> packed;
  std::vector<float> heights = field.heights;
  levels_.clear();
  for (int L = 0; L < pyramid.levels(); ++L) {
    const terrain::MinMaxLevel& level = pyramid.level(L);
    levels_.push_back({int(packed.size()), level.width, level.height, 0});
    for (int k = 0; k <= std::min(L, lodLevels_); ++k) {
      const terrain::MinMaxLevel& bounds = lod.levelBounds[size_t(k)].level(L - k);
      if (bounds.width != level.width || bounds.height != level.height)
        throw std::logic_error("TerrainPass: a LOD level's bounds do not match the pyramid's nodes");
      packed.insert(packed.end(), bounds.minimum.begin(), bounds.minimum.end());
      packed.insert(packed.end(), bounds.maximum.begin(), bounds.maximum.end());
    }
    if (L >= 1 && L <= lodLevels_) {
      const terrain::HeightField& h = lod.levels[size_t(L)];
      if (h.nx != level.width + 1 || h.ny != level.height + 1)
        throw std::logic_error("TerrainPass: a LOD level's samples do not match the pyramid's nodes");
      levels_.back()[3] = int(heights.size());
      heights.insert(heights.end(), h.heights.begin(), h.heights.end());
    }
  }
  fieldTop_ = pyramid.fieldMax();
  if (field.hasOutside()) fieldTop_ = std::max(fieldTop_, float(field.outsideHeight));
  heights_ = gpu::Buffer(context_, heights.size() * sizeof(float), gpu::BufferUsage::Storage,
                         gpu::MemoryLocation::Device, "terrain heights");
  heights_.upload(heights);
  pyramid_ = gpu::Buffer(context_, packed.size() * sizeof(float), gpu::BufferUsage::Storage,
                         gpu::MemoryLocation::Device, "terrain pyramid");
  pyramid_.upload(packed);
  resolveSeconds_ = resolved->seconds;
  resolved_ = std::move(resolved);
  horizon_.reset();
  key_ = key;
  planetRadius_ = planetRadius;
  return true;
}

double TerrainPass::groundUnderCamera() const {
  if (!resolved_) throw std::logic_error("TerrainPass: prepare before groundUnderCamera");
  const double h = resolved_->field.sample(0.0, 0.0);
  return std::isfinite(h) ? h : resolved_->settings.locationHeight_m;
}

void TerrainPass::uploadBlock(const TerrainPassView& view, const TerrainCloudShadow* shadow) {
  if (!resolved_) throw std::logic_error("TerrainPass: prepare before record");
  const terrain::HeightField& f = resolved_->field;
  const shared::TerrainAlbedoParameters& a = resolved_->settings.albedo;
  TerrainBlock b{};
  put(b.cameraPosition, view.cameraPosition, planetRadius_);
  put(b.cameraForward, view.camera.forward, view.camera.fov);
  put(b.cameraRight, view.camera.right, view.camera.yaw);
  put(b.cameraUp, view.camera.up);
  put(b.sunDirection, glm::normalize(view.sunDirection), view.selfShadow ? 1.0 : 0.0);
  b.image[0] = view.camera.width;
  b.image[1] = view.camera.height;
  b.image[2] = view.camera.projection;
  b.image[3] = std::max(view.airSteps, 1);
  b.grid[0] = float(f.x0), b.grid[1] = float(f.y0), b.grid[2] = float(f.dx), b.grid[3] = float(f.dy);
  b.gridSize[0] = f.nx, b.gridSize[1] = f.ny, b.gridSize[2] = int(levels_.size()), b.gridSize[3] = f.hasOutside();
  b.heights[0] = f.hasOutside() ? float(f.outsideHeight) : 0.0f;
  b.heights[1] = fieldTop_;
  b.heights[2] = view.skyLight == TerrainSkyLight::Clear ? 1.0f : 0.0f;
  b.heights[3] = float(std::tan(std::max(view.sunAngularRadius, 0.0)));
  if (shadow && shadow->map) {
    put(b.shadowCentre, shadow->centre, shadow->extent_m);
    put(b.shadowU, shadow->u, shadow->start_m);
    put(b.shadowV, shadow->v, 1.0);
  }
  put(b.albedoRock, a.rock, view.deckAsymmetry);
  put(b.albedoVegetation, a.vegetation);
  put(b.albedoSnow, a.snow);
  b.albedoLines[0] = float(a.treeLine), b.albedoLines[1] = float(a.treeLineTransition);
  b.albedoLines[2] = float(a.vegetationMaxSlope), b.albedoLines[3] = float(a.snowLine);
  b.albedoSlopes[0] = float(a.snowLineTransition), b.albedoSlopes[1] = float(a.snowMaxSlope);
  b.albedoSlopes[2] = float(a.slopeTransition);
  b.deck[0] = float(view.cloudMiddleRadius);
  b.deck[1] = view.skyLight == TerrainSkyLight::DeckHemisphere ? 1.0f : 0.0f;
  // The camera's cone in field cells per metre of distance; the walk's LOD starts where it passes one.
  b.lod[0] = float(std::max(view.lodFootprint, 0.0) * cameraPixelAngle(view.camera) / std::max(f.dx, f.dy));
  b.lod[1] = float(lodLevels_);
  b.skyOcclusion[0] = int(view.skyOcclusion);
  b.skyOcclusion[1] = std::max(view.occlusionRays, 1);
  if (view.skyOcclusion == TerrainSkyOcclusion::HorizonMap) {
    const terrain::HorizonMap& h = horizonMap(view.horizonAzimuths);
    b.horizonSize[0] = h.width, b.horizonSize[1] = h.height, b.horizonSize[2] = h.azimuths;
    b.horizonGrid[0] = float(h.x0), b.horizonGrid[1] = float(h.y0), b.horizonGrid[2] = float(h.dx);
    b.horizonGrid[3] = float(h.dy);
  }
  for (size_t k = 0; k < levels_.size(); ++k)
    for (int c = 0; c < 4; ++c) b.levels[k][c] = levels_[k][c];
  block_.upload(&b, sizeof(b));
}

void TerrainPass::recordCast(const TerrainPassView& view, const gpu::TileDispatch& tiles, gpu::CommandList& commands,
                             const TerrainCloudShadow* shadow) {
  uploadBlock(view, shadow);
  const VkDeviceSize pixels = VkDeviceSize(view.camera.width) * VkDeviceSize(view.camera.height);
  if (!hits_ || hits_.size() != pixels * 12 * sizeof(float))
    hits_ = gpu::Buffer(context_, pixels * 12 * sizeof(float), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device,
                        "terrain hits");
  if (!depth_ || depth_.size() != pixels * sizeof(float))
    depth_ = gpu::Buffer(context_, pixels * sizeof(float), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device,
                         "terrain depth");
  const gpu::Image& shadowMap = shadow && shadow->map ? *shadow->map : shadowPlaceholder_;
  commands.bind(cast_, {block_, heights_, pyramid_, hits_, depth_, {shadowMap, linearClamp_}, horizonBuffer_});
  TilePush castPush{tiles};
  commands.pushConstants(castPush);
  commands.dispatchTiles(tiles, "terrain/cast_terrain");
  commands.barrier();
}

void TerrainPass::record(const TerrainPassView& view, const AtmosphereLuts& luts,
                         const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& frame,
                         const gpu::TileDispatch& tiles, gpu::CommandList& commands, const TerrainCloudShadow* shadow) {
  if (skyIrradiance.size() != luts.batchCount()) throw std::logic_error("TerrainPass: one irradiance table per batch");
  recordCast(view, tiles, commands, shadow);
  const size_t batches = luts.batchCount();
  for (size_t b = 0; b < batches; ++b) {
    const AtmosphereLuts::Batch& batch = luts.batch(b);
    commands.bind(shade_, {b < view.lightBlocks.size() ? *view.lightBlocks[b] : batch.block,
                           block_,
                           heights_,
                           pyramid_,
                           {batch.transmittance, luts.linearClamp()},
                           {batch.multipleScattering, luts.linearClamp()},
                           {*skyIrradiance[b], luts.linearClamp()},
                           {batch.multipleScatteringAnisotropy, luts.linearClamp()},
                           hits_,
                           frame});
    ShadePush push{tiles, b > 0 ? 1 : 0, b + 1 == batches ? 1 : 0, view.groundOnly ? 1 : 0, 0};
    commands.pushConstants(push);
    commands.dispatchTiles(tiles, "terrain/shade_terrain");
    commands.barrier();
  }
}

std::vector<glm::vec4> TerrainPass::castRays(const std::vector<glm::vec4>& rays) {
  if (!resolved_) throw std::logic_error("TerrainPass: prepare before castRays");
  if (!castRays_)
    castRays_ = std::make_unique<gpu::ComputePipeline>(
        context_, gpu::PipelineDesc{"terrain/cast_rays_check",
                                    {gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer,
                                     gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                                     gpu::BindingType::StorageBuffer},
                                    sizeof(uint32_t)});
  TerrainPassView view;
  uploadBlock(view, nullptr);
  const uint32_t count = uint32_t(rays.size() / 2);
  gpu::Buffer in(context_, std::max<size_t>(rays.size(), 2) * sizeof(glm::vec4), gpu::BufferUsage::Storage,
                 gpu::MemoryLocation::Device, "terrain test rays");
  in.upload(rays);
  gpu::Buffer out(context_, std::max<size_t>(rays.size(), 2) * sizeof(glm::vec4), gpu::BufferUsage::Storage,
                  gpu::MemoryLocation::Device, "terrain test hits");
  gpu::CommandList commands(context_);
  commands.bind(*castRays_, {block_, heights_, pyramid_, in, out});
  commands.pushConstants(count);
  commands.dispatch((count + 63) / 64, 1, 1, "terrain/cast_rays_check");
  commands.submitAndWait();
  std::vector<glm::vec4> hits = out.download<glm::vec4>();
  hits.resize(rays.size());
  return hits;
}

}  // namespace firmament
