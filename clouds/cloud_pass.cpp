#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

namespace {

uint64_t fnv1a(const void* data, size_t bytes, uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

// The bakes that share the march's first 13 bindings and write the 14th (an image): the Beer shadow
// map, the other layers' map, the column map, the deep shadow map.
gpu::PipelineDesc cloudBakeDesc(const char* shader) {
  return {shader,
          {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
           gpu::BindingType::SampledImage, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
           gpu::BindingType::SampledImage, gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer,
           gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer,
           gpu::BindingType::SampledImage, gpu::BindingType::StorageImage},
          0};
}

}  // namespace

bool sunClearsEveryCloudSample(const CloudMarchSettings& march, const CloudView& view) {
  // A sample lies within D = maxDistance_m of the camera c along its view ray (10 % and 1 km added for
  // the last step's jitter), so its vertical is at most asin(D / |c|) from the camera's: the sun's angle
  // from it is at most the sun's angle from the camera's vertical plus that. 1 mrad kept from the horizon.
  const double r = glm::length(view.cameraPosition);
  if (!(r > 0.0)) return false;
  const double reach = 1.1 * march.maxDistance_m + 1000.0;
  const double tilt = reach >= r ? shared::kPi : std::asin(reach / r);
  const double sunFromZenith =
      std::acos(std::clamp(glm::dot(view.cameraPosition / r, glm::normalize(view.sunDirection)), -1.0, 1.0));
  return sunFromZenith + tilt < 0.5 * shared::kPi - 1e-3;
}

uint32_t cloudMarchFeatures(const CloudSettings& settings, bool weatherReach, bool sunClearsEverySample) {
  const CloudMarchSettings& m = settings.march;
  if (!m.specializeMarch) return 0xffffffffu;
  uint32_t features = 0;
  if (m.lightThroughOtherLayers && settings.layers.size() > 1) features |= 1u | (m.otherLayerMap ? 64u : 128u);
  if (m.beerShadowMap) features |= 2u;
  if (weatherReach) features |= 4u;
  // 8 is free (the light samples by transmittance, decision 0002).
  if (m.lightCone > 0.0) features |= 16u;
  if (settings.layers.size() > 1) features |= 32u;
  features |= m.columnMap ? 256u : 512u;
  if (m.deepShadowMap) features |= 1024u;
  for (const CloudLayerSettings& layer : settings.layers)
    if (layer.msR > 0.0) features |= 2048u;
  // The way behind a sample is marched only where the deep shadow map does not hold it: without the
  // map, on the Beer shadow map, or with the sun at or below some sample's horizon (its ray descends).
  // Else the march's code is left out: lavapipe ran its loop once per lit sample under an empty mask
  // (the term's cost on a cumulonimbus 1/16 sequence frame +8.5 % -> +3.0 %; docs/clouds.md
  // "Calibration").
  if ((features & 2048u) && (!usesDeepShadowMap(settings) || m.beerShadowMap || !sunClearsEverySample))
    features |= 4096u;
  return features;
}

CloudPass::CloudPass(gpu::Context& context)
    : context_(context),
      noise_(context),
      bakeShadow_(context, cloudBakeDesc("clouds/bake_shadow_map")),
      bakeOtherLayers_(context, cloudBakeDesc("clouds/bake_other_layers")),
      bakeColumns_(context, cloudBakeDesc("clouds/bake_columns")),
      bakeColumnAmbient_(context, cloudBakeDesc("clouds/bake_column_ambient")),
      bakeDeepShadow_(context, cloudBakeDesc("clouds/bake_deep_shadow")),
      upsample_(context,
                {"clouds/upsample_clouds",
                 {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer},
                 sizeof(UpsamplePush)}),
      neighbourhood_(
          context, {"clouds/temporal_neighbourhood",
                    {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                     gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer},
                    sizeof(NeighbourhoodPush)}),
      resolve_(context,
               {"clouds/temporal_resolve",
                {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                 gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer,
                 gpu::BindingType::StorageBuffer},
                sizeof(ResolvePush)}),
      block_(context, cloudBlockBytes(), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host, "cloud block"),
      counters_(context, 3 * sizeof(uint32_t), gpu::BufferUsage::Storage, gpu::MemoryLocation::Host, "cloud counters"),
      temporalBlock_(context, temporalBlockBytes(), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host,
                     "cloud temporal block") {}

void CloudPass::setWeatherMap(const CloudWeatherMap& map) {
  if (map.map.channels != 4 || map.map.pixelCount() == 0) throw std::logic_error("CloudPass: weather map must be RGBA");
  const uint32_t w = uint32_t(map.map.width), h = uint32_t(map.map.height);
  const glm::dvec4 region(map.width_m, map.height_m, map.skew.x, map.skew.y);
  const uint8_t sharp = map.sharpCoverage ? 1 : 0;
  const uint64_t hash =
      fnv1a(map.map.pixels.data(), map.map.pixels.size() * sizeof(float),
            fnv1a(&sharp, 1, fnv1a(&region, sizeof(region), fnv1a(&w, sizeof(w), fnv1a(&h, sizeof(h))))));
  if (weatherImage_ && hash == weatherHash_) return;  // the same map as the last frame's: nothing to upload
  if (!weatherImage_ || weatherImage_.width() != w || weatherImage_.height() != h)
    weatherImage_ = gpu::Image(context_, {w, h, 1, gpu::Format::RGBA32F, false, true, "cloud weather map"});
  weatherImage_.uploadFloats(map.map.pixels);
  // The coverage reach for the empty-space test on a map with sharp coverage (CloudWeatherMap).
  reachRadius_ = map.sharpCoverage ? kReachRadius_m : 0.0;
  const Image reach = map.sharpCoverage ? coverageReach(map, kReachRadius_m) : Image(1, 1, 1);
  const uint32_t rw = uint32_t(reach.width), rh = uint32_t(reach.height);
  if (!weatherReach_ || weatherReach_.width() != rw || weatherReach_.height() != rh)
    weatherReach_ = gpu::Image(context_, {rw, rh, 1, gpu::Format::R32F, false, true, "cloud weather reach"});
  weatherReach_.uploadFloats(reach.pixels);
  weatherRegion_ = region;
  weatherHash_ = hash;
  weatherTexels_ = map.map.pixels;
}

CloudSampleCounts CloudPass::sampleCounts() const {
  uint32_t c[3] = {0, 0, 0};
  counters_.download(c, sizeof(c));
  const double pixels = double(std::max<size_t>(cloudPixels_, 1));
  return {c[0] / pixels, c[1] / pixels, c[2] / pixels};
}

bool CloudPass::prepareNoise(const CloudSettings& settings, const CloudNoiseSettings& noise,
                             gpu::CommandList& commands) {
  return noise_.update(settings.seed, noise, commands);
}

void CloudPass::record(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                       const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                       const gpu::TileDispatch& tiles, gpu::CommandList& commands, const CloudAerialVolume* aerial,
                       bool continueSequence, const gpu::Buffer* terrainDepth) {
  if (settings.layers.size() > size_t(kMaxLayers))
    throw InputError("clouds: at most " + std::to_string(kMaxLayers) + " layers");
  if (skyIrradiance.size() != luts.batchCount()) throw std::logic_error("CloudPass: one irradiance table per batch");
  if (!view.lightBlocks.empty() && view.lightBlocks.size() != luts.batchCount())
    throw std::logic_error("CloudPass: one light block per batch");
  lightBlocks_ = view.lightBlocks;
  const CloudMarchSettings& m = settings.march;
  const bool volume = m.aerialPerspective == AerialPerspective::Volume;
  if (volume && (!aerial || aerial->volumes.size() != luts.batchCount() || !(aerial->maxDistance_m > 0.0)))
    throw std::logic_error("CloudPass: aerial perspective 'volume' needs one volume per spectral batch");
  std::vector<uint8_t> settingsKey = uploadBlock(settings, view, luts, volume ? aerial->maxDistance_m : 0.0);
  const auto layers = sharedCloudLayers(settings, luts.parameters().bottom_radius);
  const uint32_t zero[3] = {0, 0, 0};
  counters_.upload(zero, sizeof(zero));

  const uint32_t width = uint32_t(view.camera.width), height = uint32_t(view.camera.height);
  if (skyFrame.size() != VkDeviceSize(width) * height * 4 * sizeof(float))
    throw std::logic_error("CloudPass: the sky frame must hold the view's RGBA32F pixels");
  // The previous frame's cloud frame becomes the history; this frame writes the other.
  current_ = 1 - current_;
  for (gpu::Buffer& frame : cloudFrames_)
    if (!frame || frame.size() != skyFrame.size())
      frame =
          gpu::Buffer(context_, skyFrame.size(), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device, "cloud frame");
  gpu::Buffer& cloudFrame = cloudFrames_[current_];
  const gpu::Buffer& historyFrame = cloudFrames_[1 - current_];
  if (!depth_ || depth_.size() != VkDeviceSize(width) * height * sizeof(float))
    depth_ = gpu::Buffer(context_, VkDeviceSize(width) * height * sizeof(float), gpu::BufferUsage::Storage,
                         gpu::MemoryLocation::Device, "cloud depth");

  const TemporalPlan plan = planTemporal(m, view, layers, settingsKey, continueSequence);
  const int k = plan.k;
  placeMaps(settings, view, luts, settingsKey, plan, continueSequence, volume ? aerial->maxDistance_m : 0.0);
  int offset[2] = {0, 0};
  if (reprojected_) blockPixel(k, offset);

  // Reduced resolution: the march covers a grid d times coarser (each coarse pixel at the centre of its
  // d x d image pixels) into coarseFrame_, then clouds/upsample_clouds interpolates and composites.
  const int divisor = reprojected_ ? k : std::clamp(m.resolutionDivisor, 1, 8);
  const uint32_t coarseWidth = (width + uint32_t(divisor) - 1) / uint32_t(divisor);
  const uint32_t coarseHeight = (height + uint32_t(divisor) - 1) / uint32_t(divisor);
  const VkDeviceSize coarseBytes = VkDeviceSize(coarseWidth) * coarseHeight * 4 * sizeof(float);
  if (divisor > 1 && (!coarseFrame_ || coarseFrame_.size() != coarseBytes))
    coarseFrame_ = gpu::Buffer(context_, coarseBytes, gpu::BufferUsage::Storage, gpu::MemoryLocation::Device,
                               "coarse cloud frame");
  const gpu::TileDispatch marchTiles =
      divisor > 1
          ? gpu::tileDispatch(context_, coarseWidth, coarseHeight,
                              tiles.stride == 1 ? gpu::DispatchOrder::RowMajor : gpu::DispatchOrder::Interleaved)
          : tiles;
  gpu::Buffer& marchFrame = divisor > 1 ? coarseFrame_ : cloudFrame;
  // Samples are reported per image pixel: what a frame costs, whatever grid the march ran on.
  cloudPixels_ = size_t(width) * height;
  allocateShadowImage(m);
  if (m.beerShadowMap && !shadowBaked_) recordBake(luts, skyIrradiance, skyFrame, commands);
  shadowBaked_ = false;
  recordOtherLayerMap(settings, luts, skyIrradiance, skyFrame, commands);
  recordColumnMap(settings, luts, skyIrradiance, skyFrame, commands);
  recordDeepShadowMap(settings, luts, skyIrradiance, skyFrame, commands);
  const size_t variant = size_t(m.aerialPerspective);
  static const char* const kVariants[3] = {"clouds/render_clouds_ap_off", "clouds/render_clouds_ap_march",
                                           "clouds/render_clouds"};
  // Bit 8192: the march stops at the terrain (terrainDepth).
  const uint32_t features = cloudMarchFeatures(settings, reachRadius_ > 0.0, sunClearsEveryCloudSample(m, view)) |
                            (terrainDepth ? 8192u : 0u);
  if (!terrainDepthPlaceholder_) {
    terrainDepthPlaceholder_ = gpu::Buffer(context_, sizeof(float), gpu::BufferUsage::Storage,
                                           gpu::MemoryLocation::Device, "terrain depth placeholder");
    const float far = 1.0e30f;
    terrainDepthPlaceholder_.upload(&far, sizeof(far));
  }
  std::unique_ptr<gpu::ComputePipeline>& pipeline = pipelines_[{int(variant), features}];
  if (!pipeline)
    pipeline = std::make_unique<gpu::ComputePipeline>(
        context_,
        gpu::PipelineDesc{
            kVariants[variant],
            {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,
             gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,
             gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,  gpu::BindingType::StorageBuffer,
             gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer,
             gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,
             gpu::BindingType::SampledImage,  gpu::BindingType::StorageBuffer, gpu::BindingType::SampledImage,
             gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,  gpu::BindingType::SampledImage,
             gpu::BindingType::StorageBuffer},
            sizeof(Push),
            {features}});
  if (!volume && !aerialPlaceholder_)
    aerialPlaceholder_ =
        gpu::Image(context_, {2, 2, 2, gpu::Format::RGBA32F, false, true, "aerial perspective placeholder"});
  // A still's sub-frames (CloudMarchSettings::stillSamples; the renderer sets 1 for a sequence's frames
  // unless asked): the march alone repeats, its blue-noise value moved by s / N (stratified over the
  // step), (L, T) averaged; per batch, so that each batch's sub-frames sum before the next adds its light.
  const int subFrames = std::clamp(m.stillSamples, 1, 64);
  for (size_t batch = 0; batch < luts.batchCount(); ++batch) {
    const AtmosphereLuts::Batch& lut = luts.batch(batch);
    const gpu::Image& aerialImage = volume ? *aerial->volumes[batch] : aerialPlaceholder_;
    commands.bind(*pipeline, {lightBlock(luts, batch),
                              {lut.transmittance, luts.linearClamp()},
                              {lut.multipleScattering, luts.linearClamp()},
                              {*skyIrradiance[batch], luts.linearClamp()},
                              {noise_.shape(), noise_.linearRepeat()},
                              {noise_.detail(), noise_.linearRepeat()},
                              {noise_.curl(), noise_.linearRepeat()},
                              {noise_.blueNoise(), noise_.nearestRepeat()},
                              skyFrame,
                              marchFrame,
                              block_,
                              counters_,
                              {weatherImage_, noise_.linearRepeat()},
                              {shadowImage_, luts.linearClamp()},
                              {lut.multipleScatteringAnisotropy, luts.linearClamp()},
                              {aerialImage, luts.linearClamp()},
                              depth_,
                              {weatherReach_, noise_.linearRepeat()},
                              {otherLayerImage_, luts.linearClamp()},
                              {columnImage_, luts.linearClamp()},
                              {deepShadowImage_, luts.linearClamp()},
                              terrainDepth ? *terrainDepth : terrainDepthPlaceholder_});
    for (int sub = 0; sub < subFrames; ++sub) {
      // The ray through the centre of the d x d pixels a grid pixel stands for, or this frame's pixel of
      // each block when reprojecting (with a new blue-noise pattern: each block pixel's 16 marches differ).
      Push push{marchTiles,
                batch == 0 ? 1 : 0,
                divisor,
                divisor == 1 ? 1 : 0,
                reprojected_ ? int32_t((temporalFrame_ * 37u) % 4096u) : 0,
                {reprojected_ ? float(offset[0]) + 0.5f : 0.5f * float(divisor),
                 reprojected_ ? float(offset[1]) + 0.5f : 0.5f * float(divisor)},
                float(sub) / float(subFrames),
                1.0f / float(subFrames),
                sub,
                sub + 1 == subFrames ? 1 : 0};
      commands.pushConstants(push);
      commands.dispatchTiles(marchTiles, "clouds/render_clouds");
      if (sub + 1 < subFrames || batch + 1 < luts.batchCount() || divisor > 1) commands.barrier();
    }
  }
  if (reprojected_) {
    recordTemporalResolve(view, m, plan, coarseWidth, coarseHeight, marchTiles, tiles, offset, cloudFrame, historyFrame,
                          skyFrame, commands);
  } else if (divisor > 1) {
    commands.bind(upsample_, {coarseFrame_, cloudFrame, skyFrame});
    UpsamplePush push{tiles, int32_t(coarseWidth), int32_t(coarseHeight), divisor, 0};
    commands.pushConstants(push);
    commands.dispatchTiles(tiles, "clouds/upsample_clouds");
  }
  rememberHistory(std::move(settingsKey), view, plan);
}

}  // namespace firmament
