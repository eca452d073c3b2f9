#include "sky/sky_renderer.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "atmosphere/atmosphere_spectra.h"
#include "core/error.h"
#include "sky/scene_cloud_medium.h"
#include "sky/scene_weather.h"

namespace firmament {
namespace {

// std140 mirror of FrameBlock in shaders/sky/render_sky.glsl.
struct FrameBlock {
  float cameraPosition[4];
  float cameraForward[4];  // w = fov
  float cameraRight[4];    // w = yaw
  float cameraUp[4];
  float sunDirection[4];
  int32_t image[4];    // width, height, projection, view steps
  int32_t options[4];  // x: read the sky-view LUT
};
static_assert(sizeof(FrameBlock) == 7 * 16);

// Push constants of shaders/sky/render_sky_tables.comp: the tiles, then the 4D table size.
struct TablesPush {
  gpu::TileDispatch tiles;
  int32_t tableSize[4];  // nu, mu_s, mu, r
  float blend[4];        // the tables' solar-irradiance rescale, the weight, the mode (write, add, blend), 0
};
static_assert(sizeof(TablesPush) == sizeof(gpu::TileDispatch) + 32);

void put(float (&out)[4], const glm::dvec3& v, double w = 0.0) {
  out[0] = float(v.x);
  out[1] = float(v.y);
  out[2] = float(v.z);
  out[3] = float(w);
}

std::string formatVector(const glm::dvec3& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "%.9f %.9f %.9f", v.x, v.y, v.z);
  return text;
}

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// sky/render_sky and sky/render_sky_march: one layout (shaders/sky/render_sky.glsl), two variants.
gpu::PipelineDesc renderSkyPipeline(const char* shader) {
  return {shader,
          {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
           gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage,
           gpu::BindingType::SampledImage, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage},
          sizeof(gpu::TileDispatch) + 4 * sizeof(int32_t)};
}

}  // namespace

SkyRenderer::SkyRenderer(gpu::Context& context)
    : context_(context),
      luts_(context),
      skyViewPipeline_(
          context, {"sky/sky_view_lut",
                    {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
                     gpu::BindingType::StorageImage, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage},
                    4 * sizeof(float)}),
      skyPipeline_(context, renderSkyPipeline("sky/render_sky")),
      frameBlock_(context, sizeof(FrameBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host, "frame block"),
      lightFrameBlock_(context, sizeof(FrameBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host,
                       "light frame block") {}

PlanOptions planOptions(const SkyRenderOptions& options) {
  PlanOptions plan;
  plan.multipleScattering = options.multipleScattering;
  plan.scatteringOrders = options.multipleScattering == MultipleScattering::BrunetonTables
                              ? options.tables.scatteringOrders
                              : options.twilightTables.scatteringOrders;
  plan.skyViewLut = options.method == SkyMethod::SkyViewLut;
  plan.spectralSamples = options.luts.spectralSamples;
  plan.multipleScatteringOrders = options.luts.multipleScatteringOrders;
  plan.aerialPerspective = options.clouds.aerialPerspective;
  plan.cloudResolutionDivisor = options.clouds.resolutionDivisor;
  plan.cloudShadowMap = options.clouds.beerShadowMap;
  plan.cloudDeepShadowMap = options.clouds.deepShadowMap;
  plan.cloudLightShafts = options.clouds.lightShafts;
  plan.cloudTemporalUpdate = options.clouds.temporalUpdate;
  plan.cloudLightThroughOtherLayers = options.clouds.lightThroughOtherLayers;
  plan.cloudOtherLayerMap = options.clouds.otherLayerMap;
  plan.cloudColumnMap = options.clouds.columnMap;
  plan.night = options.night;
  return plan;
}

int resolveSpectralSamples(int requested, double sunZenithRad, bool clouds, bool tables) {
  if (requested != kSpectralSamplesAuto) return requested;
  if (clouds || tables) return 3;  // the cloud march runs once per batch; the 4D tables carry three
  return sunZenithRad * kRadToDeg >= kSpectralSamplesAutoZenithDeg ? 12 : 3;
}

// What one render() carries from step to step.
struct SkyRenderer::Frame {
  SkyRenderOptions options;               // the request, its automatic choices resolved (spectral samples)
  bool useTables = false;                 // Bruneton's 4D tables alone (--multiple-scattering tables): no f_ms
  double tablesWeight = 0.0;              // the 4D tables' share of the clear sky (1 with useTables)
  bool useSkyView = false;                // the sky-view table read per pixel (else a march per pixel per batch)
  bool derivedRecorded = false;           // the derived tables (4D tables or the ground's skylight) were recomputed
  bool lutsComputed = false;              // the atmosphere LUTs were computed (not from memory or disk)
  std::unique_ptr<CloudSettings> clouds;  // null without cloud layers
  bool terrain = false;                   // the scene has a /terrain section (sky/terrain_pass.h)
  std::shared_ptr<gpu::Buffer> output;    // RGBA32F pixels, row-major
  const EmbeddedRecording* embedded = nullptr;  // embedded mode: the host's targets
  gpu::TileDispatch tiles{};
  FrameBlock block{};                           // what frameBlock_ holds
  std::vector<const gpu::Buffer*> lightBlocks;  // the light's blocks (empty: the tables' own, the Sun)
};

RenderResult SkyRenderer::render(const Scene& scene, const SkyRenderOptions& options) {
  RenderResult result;
  Frame frame = plan(scene, options, result);
  prepareTables(frame, result);
  prepareClouds(scene, frame, result);
  gpu::CommandList commands(context_);
  recordBeforeClouds(scene, frame, result, commands);
  if (frame.clouds) recordClouds(frame, result, commands);
  resolve(scene, frame, commands, result);
  return result;
}

RenderResult SkyRenderer::record(const Scene& scene, const SkyRenderOptions& requested,
                                 const EmbeddedRecording& targets) {
  if (!targets.commands || !targets.colour || !targets.depth)
    throw InputError("embedded mode: a command buffer, a colour view and a depth view are all needed");
  SkyRenderOptions options = requested;
  options.downloadImages = false;
  // One spectral batch: the exported lookups and the composite read batch 0 (clouds need it too).
  if (options.luts.spectralSamples == kSpectralSamplesAuto) options.luts.spectralSamples = 3;
  if (options.luts.spectralSamples != 3)
    throw InputError("embedded mode renders three wavelengths (spectral samples 3)");
  if (options.multipleScattering == MultipleScattering::BrunetonTables)
    throw InputError("embedded mode needs the f_ms path (--multiple-scattering fms or auto)");
  // The host's shaders read the f_ms path's lookups (EmbeddedLookups): auto stays on it.
  options.multipleScattering = MultipleScattering::HillaireFms;
  RenderResult result;
  Frame frame = plan(scene, options, result);
  frame.embedded = &targets;
  prepareTables(frame, result);
  prepareClouds(scene, frame, result);
  // The previous frame's pass timings (its commands have finished: one frame in flight), then this
  // frame's list, kept until the next record() (its queries are read then).
  if (embeddedCommands_ && embeddedCommands_->readTimings())
    for (const gpu::PassTiming& t : embeddedCommands_->passTimings()) {
      result.timings.push_back(t);
      result.frameMilliseconds += t.milliseconds;
    }
  embeddedCommands_ = std::make_unique<gpu::CommandList>(context_, targets.commands);
  gpu::CommandList& commands = *embeddedCommands_;
  recordBeforeClouds(scene, frame, result, commands);
  if (frame.clouds) {
    recordClouds(frame, result, commands);  // the host's depth before the march
    commands.barrier();
    recordHostWrite(frame, commands);
  } else {
    recordHostDepth(frame, result, commands, false);  // and the host's image written in the same pass
  }
  commands.finish();
  if (frame.clouds) result.cloudsReprojected = clouds_->lastFrameReprojected();
  return result;
}

// What both ways of running record before the clouds: the sky, the night's light added to it, the
// night's choice of the light, and a terrain that no cloud pass will shadow.
void SkyRenderer::recordBeforeClouds(const Scene& scene, Frame& frame, RenderResult& result,
                                     gpu::CommandList& commands) {
  recordSky(frame, result, commands);
  if (result.night.run) recordNight(scene, frame, result, commands);
  if (!result.night.run && result.night.dayMoonDisc) recordDayMoonDisc(scene, frame, result, commands);
  if (result.night.run && (frame.terrain || frame.clouds)) chooseLight(frame, result);
  if (frame.terrain && !frame.clouds) {
    commands.barrier();
    recordTerrain(frame, result, commands, nullptr);
  }
}

void SkyRenderer::recordHostDepth(Frame& frame, RenderResult& result, gpu::CommandList& commands, bool aerialRecorded) {
  const SceneView& view = result.view;
  const EmbeddedRecording& targets = *frame.embedded;
  if (!aerialRecorded) {
    // The volume over the clouds' march limit when they march, else 80 km (Hillaire 2020's 32 slices
    // over it: the first ends at 78 m); the host's far plane beyond it reads the last slice.
    AerialPerspectiveVolumeSettings settings = frame.options.aerialPerspective;
    if (!(settings.maxDistance_m > 0.0))
      settings.maxDistance_m = frame.clouds ? frame.clouds->march.maxDistance_m : 80000.0;
    if (!aerial_) aerial_ = std::make_unique<AerialPerspectiveVolume>(context_);
    commands.barrier();
    aerial_->record(settings, glm::dvec3(0.0, 0.0, view.cameraRadius), view.sunDirection, view.camera, luts_, commands);
    embeddedAerialDistance_m_ = settings.maxDistance_m;
  }
  commands.barrier();
  const int width = view.camera.width, height = view.camera.height;
  const VkDeviceSize distanceBytes = VkDeviceSize(width) * VkDeviceSize(height) * sizeof(float);
  if (!hostDistance_ || hostDistance_.size() != distanceBytes)
    hostDistance_ =
        gpu::Buffer(context_, distanceBytes, gpu::BufferUsage::Storage, gpu::MemoryLocation::Device, "host distance");
  if (!farPlaceholder_) {
    farPlaceholder_ = gpu::Buffer(context_, sizeof(float), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device,
                                  "no terrain depth");
    const float far = 1.0e30f;
    farPlaceholder_.upload(&far, sizeof(far));
  }
  if (!nearestClamp_)
    nearestClamp_ = std::make_unique<gpu::Sampler>(context_, gpu::Filter::Nearest, gpu::AddressMode::Clamp);
  const int variant = targets.colourHalf ? 0 : 1;
  if (!embedPipelines_[variant])
    embedPipelines_[variant] = std::make_unique<gpu::ComputePipeline>(
        context_, gpu::PipelineDesc{
                      variant == 0 ? "sky/embed_composite_rgba16f" : "sky/embed_composite_rgba32f",
                      {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::StorageImage,
                       gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                       gpu::BindingType::StorageBuffer},
                      sizeof(gpu::TileDispatch) + 5 * 4 * sizeof(float)});
  // The lookups a host's shader reads (firmament/atmosphere_lookup.glsl's FirmamentAtmosphere).
  const shared::AtmosphereParameters& a = luts_.batch(0).parameters;
  const glm::dvec3 sunTop = threeWavelengthRadianceToRgb(frame.options.luts.wavelengthsNm, kSunLambdaPower) *
                            glm::dvec3(a.solar_irradiance.x, a.solar_irradiance.y, a.solar_irradiance.z);
  lookups_.transmittance = &luts_.batch(0).transmittance;
  lookups_.aerialPerspective = &aerial_->volume(0);
  const float parameters[4][4] = {
      {float(a.bottom_radius), float(a.top_radius), float(view.cameraRadius), float(embeddedAerialDistance_m_)},
      {float(view.sunDirection.x), float(view.sunDirection.y), float(view.sunDirection.z), float(a.mie_phase_g)},
      {float(sunTop.x), float(sunTop.y), float(sunTop.z), 0.0f},
      {float(width), float(height), 0.0f, 0.0f}};
  std::memcpy(lookups_.parameters, parameters, sizeof(parameters));
  commands.bind(*embedPipelines_[variant], {frameBlock_,
                                            {gpu::ExternalView{targets.depth, targets.depthLayout}, *nearestClamp_},
                                            gpu::ExternalView{targets.colour, VK_IMAGE_LAYOUT_GENERAL},
                                            {aerial_->volume(0), luts_.linearClamp()},
                                            *frame.output,
                                            hostDistance_,
                                            frame.terrain ? terrain_->depth() : farPlaceholder_});
  struct {
    gpu::TileDispatch tiles;
    float depth[4];
    float atmosphere[4][4];
  } push{frame.tiles,
         {float(targets.near_m), float(targets.far_m), targets.reversedDepth ? 1.0f : 0.0f, frame.clouds ? 0.0f : 2.0f},
         {}};
  std::memcpy(push.atmosphere, parameters, sizeof(parameters));
  commands.pushConstants(push);
  commands.dispatchTiles(frame.tiles, "sky/embed_host_depth");
}

void SkyRenderer::recordHostWrite(Frame& frame, gpu::CommandList& commands) {
  const EmbeddedRecording& targets = *frame.embedded;
  const int variant = targets.colourHalf ? 0 : 1;
  commands.bind(*embedPipelines_[variant], {frameBlock_,
                                            {gpu::ExternalView{targets.depth, targets.depthLayout}, *nearestClamp_},
                                            gpu::ExternalView{targets.colour, VK_IMAGE_LAYOUT_GENERAL},
                                            {aerial_->volume(0), luts_.linearClamp()},
                                            *frame.output,
                                            hostDistance_,
                                            farPlaceholder_});
  struct {
    gpu::TileDispatch tiles;
    float depth[4];
    float atmosphere[4][4];
  } push{frame.tiles, {0.0f, 0.0f, 0.0f, 1.0f}, {}};
  commands.pushConstants(push);
  commands.dispatchTiles(frame.tiles, "sky/embed_write");
}

// Plan: the scene's view, the options' automatic choices, the passes the scene needs (render_plan.h).
SkyRenderer::Frame SkyRenderer::plan(const Scene& scene, const SkyRenderOptions& requested, RenderResult& result) {
  Frame frame;
  frame.useTables = requested.multipleScattering == MultipleScattering::BrunetonTables;
  result.view = makeSceneView(scene);
  frame.options = requested;
  // Terrain: the camera stands on the field at the location (sky/terrain_pass.h).
  frame.terrain = scene.hasSection("terrain");
  if (frame.terrain) {
    if (!terrain_) terrain_ = std::make_unique<TerrainPass>(context_);
    terrain_->prepare(scene, result.view.atmosphere.bottomRadius);
    result.view.cameraRadius = result.view.atmosphere.bottomRadius + terrain_->groundUnderCamera() +
                               scene.number("/camera/height_above_ground_m");
  }
  const bool hasClouds = sceneHasCloudLayers(scene);
  if (hasClouds && frame.useTables)
    throw InputError("clouds need the f_ms path (--multiple-scattering fms) in this version");
  if (scene.hasSection("terrain") && frame.useTables)
    throw InputError("terrain needs the f_ms path (--multiple-scattering fms) in this version");
  frame.options.luts.spectralSamples =
      resolveSpectralSamples(frame.options.luts.spectralSamples, result.view.sunZenith, hasClouds, frame.useTables);
  result.spectralSamples = frame.options.luts.spectralSamples;
  const PlanOptions planned = planOptions(frame.options);
  result.plan = planRender(scene, planned);
  frame.tablesWeight = sceneTablesWeight(scene, planned);
  result.tablesWeight = frame.tablesWeight;
  const bool skyView = !frame.useTables && frame.options.method == SkyMethod::SkyViewLut &&
                       result.view.cameraRadius <=
                           atmosphereParametersAt(result.view.atmosphere, frame.options.luts.wavelengthsNm).top_radius;
  result.night = decideNight(scene, frame.options.night, skyView);
  result.light.direction = result.view.sunDirection;  // the Sun, unless the night's light is the Moon
  result.light.reason = "the Sun";
  if (hasClouds) {
    frame.clouds = std::make_unique<CloudSettings>(CloudSettings::fromScene(scene));
    frame.options.clouds.apply(frame.clouds->march);
    // A still's sub-frames only for stills, unless the knob was set for every frame (decision 0149).
    if (!frame.options.still && !frame.options.clouds.stillSamples) frame.clouds->march.stillSamples = 1;
    // The terrain's cloud shadows come from the Beer shadow map: baked whenever there is terrain.
    if (frame.terrain) frame.clouds->march.beerShadowMap = true;
  }
  return frame;
}

// Prepare the tables, in their own submission so that their cost is reported apart from the frame's:
// the atmosphere LUTs, then the tables derived from them (the 4D scattering tables, or the f_ms path's
// ground skylight). Each is reused while its inputs are unchanged.
void SkyRenderer::prepareTables(Frame& frame, RenderResult& result) {
  const SkyRenderOptions& options = frame.options;
  AtmosphereLutSettings lutSettings = options.luts;
  lutSettings.multipleScatteringLut = !frame.useTables;  // the 4D tables replace Psi_ms
  AtmosphereLuts::Update tables = luts_.update(result.view.atmosphere, lutSettings);
  for (const auto& t : tables.timings) {
    result.timings.push_back(t);
    result.precomputeMilliseconds += t.milliseconds;
  }
  gpu::CommandList derived(context_);
  bool recorded = false;
  if (frame.tablesWeight > 0.0) {
    // One set per spectral batch; kept while the atmosphere and settings are unchanged (the Sun's distance
    // is not in their key: they are rescaled at lookup).
    tables_.resize(luts_.batchCount());
    for (size_t b = 0; b < luts_.batchCount(); ++b) {
      if (!tables_[b]) tables_[b] = std::make_unique<ScatteringTables>(context_);
      recorded =
          tables_[b]->update(luts_, b, frame.useTables ? options.tables : options.twilightTables, derived) || recorded;
    }
  }
  if (!frame.useTables) {
    fmsSkyIrradiance_.resize(luts_.batchCount());
    for (size_t b = 0; b < luts_.batchCount(); ++b) {
      if (!fmsSkyIrradiance_[b]) fmsSkyIrradiance_[b] = std::make_unique<FmsSkyIrradiance>(context_);
      recorded = fmsSkyIrradiance_[b]->update(luts_, b, options.fmsSkyIrradiance, derived) || recorded;
    }
  }
  if (recorded) {
    derived.submitAndWait();
    for (const auto& t : derived.passTimings()) {
      result.timings.push_back(t);
      result.precomputeMilliseconds += t.milliseconds;
    }
    if (frame.tablesWeight > 0.0)
      for (size_t b = 0; b < luts_.batchCount(); ++b) tables_[b]->store();
  }
  frame.derivedRecorded = recorded;
  frame.lutsComputed = tables.source == AtmosphereLuts::Source::Computed;
  result.tablesReused = !frame.lutsComputed && !recorded;
  result.tablesSource = frame.lutsComputed                                ? "computed"
                        : tables.source == AtmosphereLuts::Source::Memory ? "memory"
                                                                          : "disk cache";
}

// Prepare the clouds (docs/clouds/README.md): the weather map of the scene's time, and the noise, baked once
// per seed apart from the frame's passes.
void SkyRenderer::prepareClouds(const Scene& scene, Frame& frame, RenderResult& result) {
  if (!frame.clouds) return;
  if (!clouds_) clouds_ = std::make_unique<CloudPass>(context_);
  // The weather map (sky/scene_weather.h): the simulation's (CPU, cached) or the procedural one.
  clouds_->setWeatherMap(frame.options.cloudWeather ? *frame.options.cloudWeather : cloudWeatherMapForScene(scene));
  gpu::CommandList bake(context_);
  if (clouds_->prepareNoise(*frame.clouds, frame.options.cloudNoise, bake)) {
    bake.submitAndWait();
    clouds_->noise().storeBaked();
    for (const auto& t : bake.passTimings()) {
      result.timings.push_back(t);
      result.precomputeMilliseconds += t.milliseconds;
    }
  }
  result.cloudNoiseSource = clouds_->noise().source();
}

// Record the sky: the frame block, the sky-view table (when its inputs changed), then the image's
// in-scattering by one of three methods (the sky-view table, a march per pixel, the 4D tables).
void SkyRenderer::recordSky(Frame& frame, RenderResult& result, gpu::CommandList& commands) {
  const SkyRenderOptions& options = frame.options;
  const SceneView& view = result.view;
  const int width = view.camera.width;
  const int height = view.camera.height;
  const bool useTables = frame.useTables;
  FrameBlock block{};
  put(block.cameraPosition, glm::dvec3(0.0, 0.0, view.cameraRadius));
  put(block.cameraForward, view.camera.forward, view.camera.fov);
  put(block.cameraRight, view.camera.right, view.camera.yaw);
  put(block.cameraUp, view.camera.up);
  put(block.sunDirection, view.sunDirection);
  block.image[0] = width;
  block.image[1] = height;
  block.image[2] = view.camera.projection;
  block.image[3] = options.viewSteps;
  // The sky-view table holds the sky seen from inside the atmosphere; from above its top every
  // pixel is marched (the same integral, so there is no seam at the switch).
  const bool useSkyView =
      !useTables && options.method == SkyMethod::SkyViewLut && view.cameraRadius <= luts_.parameters().top_radius;
  frame.useSkyView = useSkyView;
  result.methodUsed = useSkyView ? SkyMethod::SkyViewLut : SkyMethod::PerPixel;
  block.options[0] = useSkyView ? 1 : 0;
  frameBlock_.upload(&block, sizeof(block));
  frame.block = block;
  if (!skyView_ || int(skyView_.width()) != options.skyViewWidth || int(skyView_.height()) != options.skyViewHeight) {
    skyView_ = gpu::Image(context_, {uint32_t(options.skyViewWidth), uint32_t(options.skyViewHeight), 1,
                                     gpu::Format::RGBA32F, true, true, "sky-view LUT"});
    skyViewKey_.clear();
  }

  // The frame is a storage buffer of RGBA32F pixels, row-major, not a storage image: on lavapipe an
  // image store costs ~4x a buffer store (eval/micro/output_write.cpp, docs/gpu.md), and it is read back as is.
  const VkDeviceSize frameBytes = VkDeviceSize(width) * VkDeviceSize(height) * 4 * sizeof(float);
  if (frame.embedded) {  // kept past record(): the host runs the commands later
    if (!embeddedOutput_ || embeddedOutput_->size() != frameBytes)
      embeddedOutput_ = std::make_shared<gpu::Buffer>(context_, frameBytes, gpu::BufferUsage::Storage,
                                                      gpu::MemoryLocation::Device, "sky frame");
    frame.output = embeddedOutput_;
  } else {
    frame.output = std::make_shared<gpu::Buffer>(context_, frameBytes, gpu::BufferUsage::Storage,
                                                 gpu::MemoryLocation::Device, "sky frame");
  }
  gpu::Buffer& output = *frame.output;
  frame.tiles = gpu::tileDispatch(context_, uint32_t(width), uint32_t(height), options.dispatchOrder);
  const gpu::TileDispatch& tiles = frame.tiles;
  const size_t batches = luts_.batchCount();
  // The sky-view table is a function of the tables, the camera's altitude, the sun's zenith angle and
  // the steps only (azimuths are measured from the sun): a sequence's frame keeps the previous frame's
  // when those are unchanged (the camera turns under a fixed sun), bit for bit the same table. A still
  // computes it, so its frame time is a whole frame's.
  std::string skyViewKey;
  if (useSkyView) {
    char inputs[160];  // the floats the pass is given, exactly (%a)
    std::snprintf(inputs, sizeof(inputs), "|%a|%a|%d|%dx%d", double(float(view.cameraRadius)),
                  double(float(view.sunDirection.z)), options.viewSteps, options.skyViewWidth, options.skyViewHeight);
    skyViewKey = luts_.key() + inputs;
  }
  if (frame.derivedRecorded || frame.lutsComputed) skyViewKey_.clear();  // inputs recomputed
  result.skyViewReused = options.continueSequence && useSkyView && !skyViewKey_.empty() && skyViewKey == skyViewKey_;
  if (useSkyView && !result.skyViewReused && frame.tablesWeight < 1.0) {
    skyViewKey_ = skyViewKey;
    // One sky-view pass per spectral batch, each adding its Rec.709 contribution.
    for (size_t b = 0; b < batches; ++b) {
      const AtmosphereLuts::Batch& batch = luts_.batch(b);
      struct {
        float cameraRadius;
        float muS;
        int32_t steps;
        int32_t accumulate;
      } push{float(view.cameraRadius), float(view.sunDirection.z), options.viewSteps, b > 0 ? 1 : 0};
      commands.bind(skyViewPipeline_, {batch.block,
                                       {batch.transmittance, luts_.linearClamp()},
                                       {batch.multipleScattering, luts_.linearClamp()},
                                       skyView_,
                                       {fmsSkyIrradiance_[b]->irradiance(), luts_.linearClamp()},
                                       {batch.multipleScatteringAnisotropy, luts_.linearClamp()}});
      commands.pushConstants(push);
      commands.dispatch(uint32_t((options.skyViewWidth + 7) / 8), uint32_t((options.skyViewHeight + 7) / 8), 1,
                        "sky/sky_view_lut");
      commands.barrier();
    }
  }
  // The image: one pass reading the sky-view table, or one march per spectral batch (f_ms), unless the
  // 4D tables alone make the sky.
  const bool fmsSky = !useTables && frame.tablesWeight < 1.0;
  const size_t renderPasses = !fmsSky ? 0 : useSkyView ? 1 : batches;
  if (fmsSky && !useSkyView && !skyMarchPipeline_)
    skyMarchPipeline_ = std::make_unique<gpu::ComputePipeline>(context_, renderSkyPipeline("sky/render_sky_march"));
  const gpu::ComputePipeline* skyPipeline =
      useSkyView ? &skyPipeline_ : skyMarchPipeline_.get();  // null with the 4D tables
  for (size_t b = 0; b < renderPasses; ++b) {
    const AtmosphereLuts::Batch& batch = luts_.batch(b);
    struct {
      gpu::TileDispatch tiles;
      int32_t accumulate;
      int32_t drawSun;
      int32_t last;
      int32_t pad;
    } push{tiles, b > 0 ? 1 : 0, b == 0 ? 1 : 0, b + 1 == renderPasses ? 1 : 0, 0};
    commands.bind(*skyPipeline, {batch.block,
                                 {batch.transmittance, luts_.linearClamp()},
                                 {batch.multipleScattering, luts_.linearClamp()},
                                 output,
                                 frameBlock_,
                                 {skyView_, luts_.linearClamp()},
                                 {luts_.sunRadiance(), luts_.linearClamp()},
                                 {fmsSkyIrradiance_[b]->irradiance(), luts_.linearClamp()},
                                 {batch.multipleScatteringAnisotropy, luts_.linearClamp()}});
    commands.pushConstants(push);
    commands.dispatchTiles(tiles, useSkyView ? "sky/render_sky" : "sky/render_sky_march");
    if (b + 1 < renderPasses) commands.barrier();
  }
  if (frame.tablesWeight > 0.0) {
    // Bruneton 2017: the in-scattering is a lookup in the 4D tables, no march; one pass per spectral batch,
    // the first writing the frame (or blending it over the f_ms sky), the others adding.
    if (!skyTablesPipeline_)
      skyTablesPipeline_ = std::make_unique<gpu::ComputePipeline>(
          context_, gpu::PipelineDesc{
                        "sky/render_sky_tables",
                        {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage,
                         gpu::BindingType::SampledImage, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
                         gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer},
                        sizeof(TablesPush)});
    const gpu::Sampler& linear = luts_.linearClamp();
    const float weight = float(frame.tablesWeight);
    for (size_t b = 0; b < batches; ++b) {
      const ScatteringTables& tables = *tables_[b];
      const ScatteringTableSettings& t = tables.settings();
      const float mode = b > 0 ? 1.0f : fmsSky ? 2.0f : 0.0f;
      const float rescale = float(luts_.solarIrradianceScale() / tables.solarIrradianceScale());
      TablesPush push{tiles, {t.nuSize, t.muSSize, t.muSize, t.rSize}, {rescale, weight, mode, 0.0f}};
      if (fmsSky || b > 0) commands.barrier();
      commands.bind(*skyTablesPipeline_, {luts_.batch(b).block,
                                          {luts_.batch(b).transmittance, linear},
                                          {tables.scattering(), linear},
                                          {tables.singleMieScattering(), linear},
                                          {tables.irradiance(), linear},
                                          output,
                                          frameBlock_});
      commands.pushConstants(push);
      commands.dispatchTiles(tiles, "sky/render_sky_tables");
    }
  }
}

// Record the night (sky/night_pass.h): added to the sky frame before the clouds composite over it.
void SkyRenderer::recordNight(const Scene& scene, Frame& frame, RenderResult& result, gpu::CommandList& commands) {
  if (!night_) night_ = std::make_unique<NightPass>(context_);
  NightPass::Inputs in;
  in.scene = &scene;
  in.decision = &result.night;
  in.luts = &luts_;
  in.lutSettings = &frame.options.luts;
  for (const auto& irradiance : fmsSkyIrradiance_) in.skyIrradiance.push_back(&irradiance->irradiance());
  in.frameBlock = &frameBlock_;
  in.output = frame.output.get();
  in.tiles = frame.tiles;
  in.camera = result.view.camera;
  in.cameraRadius = result.view.cameraRadius;
  in.solarIrradianceScale = result.view.atmosphere.solarIrradianceScale;
  in.viewSteps = frame.options.viewSteps;
  in.skyViewWidth = frame.options.skyViewWidth;
  in.skyViewHeight = frame.options.skyViewHeight;
  commands.barrier();
  night_->record(in, commands);
}

// The daytime Moon (sky/night_pass.h): the disc alone over its pixels, before the clouds composite.
void SkyRenderer::recordDayMoonDisc(const Scene& scene, Frame& frame, RenderResult& result,
                                    gpu::CommandList& commands) {
  if (!dayMoon_) dayMoon_ = std::make_unique<DayMoonDiscPass>(context_);
  DayMoonDiscPass::Inputs in;
  in.scene = &scene;
  in.luts = &luts_;
  in.frameBlock = &frameBlock_;
  in.output = frame.output.get();
  in.camera = result.view.camera;
  result.night.dayMoonDisc = dayMoon_->record(in, commands);
}

// The light of the clouds and terrain at night (decision 0228): each light's horizontal ground illuminance
// at the camera's ground point from the tables (read back), the brighter one carrying both. The Sun's
// own blocks stay bound while it is the light (and its frame's pixels unchanged while the Moon is under
// 1e-4 of it).
void SkyRenderer::chooseLight(Frame& frame, RenderResult& result) {
  const SceneView& view = result.view;
  std::vector<const gpu::Image*> irradiance;
  for (const auto& t : fmsSkyIrradiance_) irradiance.push_back(&t->irradiance());
  const std::vector<SpectralBatch> spectra =
      spectralBatches(frame.options.luts.spectralSamples, frame.options.luts.wavelengthsNm);
  const TableGroundIlluminance ground(luts_, irradiance, spectra);
  const double r = std::max(view.cameraRadius, luts_.parameters().bottom_radius);
  const std::vector<glm::dvec3> sunScale(spectra.size(), glm::dvec3(1.0));
  const astro::MoonLight& moon = night_->moon();
  const std::vector<glm::dvec3> moonScale = moonChannelScale(moon, spectra, view.atmosphere.solarIrradianceScale);
  const double sunLux = ground.lux(r, view.sunDirection.z, sunScale);
  const double moonLux = ground.lux(r, moon.directionEnu.z, moonScale);
  result.light = chooseFrameLight(sunLux, moonLux, view.sunDirection, moon.directionEnu);
  result.light.channelScale = result.light.moon ? moonScale : sunScale;
  frame.lightBlocks.clear();
  if (!result.light.moon && result.light.scale == 1.0) return;  // the tables' own blocks
  uploadLightBlocks(context_, luts_, spectra, result.light, lightBlocks_);
  for (const gpu::Buffer& b : lightBlocks_) frame.lightBlocks.push_back(&b);
}

// Record the clouds: the Beer shadow map (when on), the aerial-perspective volume they read (with the
// clouds' light shafts), then the cloud march composited over the sky.
void SkyRenderer::recordClouds(Frame& frame, RenderResult& result, gpu::CommandList& commands) {
  const SkyRenderOptions& options = frame.options;
  const SceneView& view = result.view;
  const size_t batches = luts_.batchCount();
  gpu::Buffer& output = *frame.output;
  const gpu::TileDispatch& tiles = frame.tiles;
  const CloudSettings& clouds = *frame.clouds;
  CloudView cloudView;
  cloudView.cameraPosition = glm::dvec3(0.0, 0.0, view.cameraRadius);
  cloudView.sunDirection = result.light.direction;
  cloudView.camera = view.camera;
  cloudView.lightBlocks = frame.lightBlocks;
  // The aerial-perspective volume (only when the clouds read it), over the clouds' march limit by
  // default; the barrier before the clouds covers it and the sky frame.
  CloudAerialVolume aerialVolume;
  std::vector<const gpu::Image*> irradiance;
  for (size_t b = 0; b < batches; ++b) irradiance.push_back(&fmsSkyIrradiance_[b]->irradiance());
  const CloudMarchSettings& march = clouds.march;
  const bool volume = march.aerialPerspective == AerialPerspective::Volume;
  AerialPerspectiveVolumeSettings aerialSettings = options.aerialPerspective;
  if (!(aerialSettings.maxDistance_m > 0.0)) aerialSettings.maxDistance_m = march.maxDistance_m;
  // Light shafts: the shadow map is baked first, for the volume to read
  // (docs/clouds/aerial-perspective-and-light-shafts.md).
  const bool shafts = volume && march.beerShadowMap && march.lightShafts;
  if (march.beerShadowMap)
    clouds_->recordShadowMap(clouds, cloudView, luts_, irradiance, output, volume ? aerialSettings.maxDistance_m : 0.0,
                             commands);
  if (volume) {
    if (!aerial_) aerial_ = std::make_unique<AerialPerspectiveVolume>(context_);
    AerialCloudShadow shadow;
    if (shafts) {
      const CloudPass::ShadowPlacement& p = clouds_->shadowPlacement();
      shadow = {&clouds_->shadowMap(), &luts_.linearClamp(), p.centre, p.u, p.v, p.extent_m, p.start_m};
    }
    aerial_->record(aerialSettings, cloudView.cameraPosition, cloudView.sunDirection, view.camera, luts_, commands,
                    shafts ? &shadow : nullptr, frame.lightBlocks);
    aerialVolume.volumes = aerial_->volumes();
    aerialVolume.maxDistance_m = aerialSettings.maxDistance_m;
  }
  commands.barrier();
  if (shafts) {
    if (!lightShaftsPipeline_)
      lightShaftsPipeline_ = std::make_unique<gpu::ComputePipeline>(
          context_, gpu::PipelineDesc{"sky/cloud_light_shafts",
                                      {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage,
                                       gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer},
                                      sizeof(gpu::TileDispatch) + 4 * sizeof(float)});
    struct {
      gpu::TileDispatch tiles;
      float maxDistance;
      float pad[3];
    } push{tiles, float(aerialSettings.maxDistance_m), {0.0f, 0.0f, 0.0f}};
    // Under the Moon the shafts' phase angle is the Moon's: the frame block with its direction.
    const bool moon = !frame.lightBlocks.empty();
    if (moon) {
      FrameBlock lightBlock = frame.block;
      put(lightBlock.sunDirection, cloudView.sunDirection);
      lightFrameBlock_.upload(&lightBlock, sizeof(lightBlock));
    }
    commands.bind(*lightShaftsPipeline_, {moon ? *frame.lightBlocks[0] : luts_.batch(0).block,
                                          {*aerial_->volumes()[0], luts_.linearClamp()},
                                          output,
                                          moon ? lightFrameBlock_ : frameBlock_});
    commands.pushConstants(push);
    commands.dispatchTiles(tiles, "sky/cloud_light_shafts");
    commands.barrier();
  }
  if (frame.terrain) {
    const CloudPass::ShadowPlacement& p = clouds_->shadowPlacement();
    const TerrainCloudShadow shadow{&clouds_->shadowMap(), p.centre, p.u, p.v, p.extent_m, p.start_m};
    recordTerrain(frame, result, commands, &shadow);
  }
  // Embedded mode: the host's pixels enter the frame before the march, which stops at their distance.
  const gpu::Buffer* stopAt = frame.terrain ? &terrain_->depth() : nullptr;
  if (frame.embedded) {
    if (volume) embeddedAerialDistance_m_ = aerialSettings.maxDistance_m;
    recordHostDepth(frame, result, commands, volume);
    commands.barrier();
    stopAt = &hostDistance_;
  }
  clouds_->record(clouds, cloudView, luts_, irradiance, output, tiles, commands, &aerialVolume,
                  options.continueSequence, stopAt);
}

void SkyRenderer::recordTerrain(Frame& frame, RenderResult& result, gpu::CommandList& commands,
                                const TerrainCloudShadow* shadow) {
  const SceneView& view = result.view;
  TerrainPassView terrainView;
  terrainView.cameraPosition = glm::dvec3(0.0, 0.0, double(float(view.cameraRadius)));
  terrainView.sunDirection = result.light.direction;
  terrainView.camera = view.camera;
  terrainView.lightBlocks = frame.lightBlocks;
  terrainView.airSteps = frame.options.viewSteps;
  terrainView.selfShadow = frame.options.terrain.selfShadow;
  terrainView.skyLight = frame.options.terrain.skyLight;
  terrainView.skyOcclusion = frame.options.terrain.skyOcclusion;
  terrainView.horizonAzimuths = frame.options.terrain.horizonAzimuths;
  terrainView.occlusionRays = frame.options.terrain.occlusionRays;
  terrainView.groundOnly = frame.options.terrain.groundOnly;
  terrainView.lodFootprint = frame.options.terrain.lodFootprint;
  if (frame.options.terrain.penumbra) terrainView.sunAngularRadius = luts_.parameters().sun_angular_radius;
  if (frame.clouds) {
    terrainView.deckAsymmetry = cloudPhaseMeanCosine(frame.clouds->lighting);
    const std::vector<shared::CloudLayer> layers = sharedCloudLayers(*frame.clouds, luts_.parameters().bottom_radius);
    for (const shared::CloudLayer& l : layers)
      terrainView.cloudMiddleRadius += 0.5 * (l.bottom_radius + l.top_radius) / double(layers.size());
  }
  std::vector<const gpu::Image*> irradiance;
  for (size_t b = 0; b < luts_.batchCount(); ++b) irradiance.push_back(&fmsSkyIrradiance_[b]->irradiance());
  terrain_->record(terrainView, luts_, irradiance, *frame.output, frame.tiles, commands, shadow);
}

// Resolve: submit and wait, the timings, the images downloaded (unless the caller keeps them on the
// GPU), and the image's metadata.
void SkyRenderer::resolve(const Scene& scene, Frame& frame, gpu::CommandList& commands, RenderResult& result) {
  const SkyRenderOptions& options = frame.options;
  const SceneView& view = result.view;
  const int width = view.camera.width;
  const int height = view.camera.height;
  gpu::Buffer& output = *frame.output;
  const bool clouds = frame.clouds != nullptr;
  commands.submitAndWait();
  for (const auto& t : commands.passTimings()) {
    result.timings.push_back(t);
    result.frameMilliseconds += t.milliseconds;
  }
  result.timingNote = commands.timingNote();

  if (options.downloadImages) {
    result.image = Image(width, height, 4);
    result.image.pixels = output.download<float>();
  }
  if (clouds) {
    if (options.downloadImages) {
      result.clouds = Image(width, height, 4);
      result.clouds.pixels = clouds_->cloudFrame().download<float>();
    }
    result.cloudSamples = clouds_->sampleCounts();
    result.cloudsReprojected = clouds_->lastFrameReprojected();
  }
  Image& image = result.image;
  image.metadata["firmament.scene_hash"] = scene.hash();
  image.metadata["firmament.device"] = context_.description();
  image.metadata["firmament.sun_direction_enu"] = formatVector(view.sunDirection);
  char sun[64];
  std::snprintf(sun, sizeof(sun), "zenith %.6f deg, azimuth %.6f deg", view.sunZenith * kRadToDeg,
                view.sunAzimuth * kRadToDeg);
  image.metadata["firmament.sun"] = sun;
  image.metadata["firmament.camera"] = scene.at("/camera").dump();
  image.metadata["firmament.units"] = "linear Rec.709, cd/m^2";
  for (const auto& t : result.timings) {
    char ms[32];
    std::snprintf(ms, sizeof(ms), "%.4f", t.milliseconds);
    image.metadata["firmament.timing." + t.label + "_ms"] = ms;
  }
}

std::vector<float> SkyRenderer::cloudShadowMap() const {
  if (!clouds_ || !clouds_->shadowMap()) return {};
  return clouds_->shadowMap().downloadFloats();
}

}  // namespace firmament
