#pragma once
// The public facade: a scene in, an HDR image out (linear Rec.709, cd/m²), with the pass plan and
// per-pass GPU timings. A host application keeps one SkyRenderer per Vulkan context; tables that
// depend only on parameters (atmosphere LUTs) are reused across frames.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_luts.h"
#include "atmosphere/fms_sky_irradiance.h"
#include "atmosphere/scattering_tables.h"
#include "clouds/cloud_pass.h"
#include "clouds/cloud_settings.h"
#include "core/image.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "gpu/dispatch.h"
#include "sky/aerial_perspective_volume.h"
#include "sky/frame_light.h"
#include "sky/night_pass.h"
#include "sky/render_plan.h"
#include "sky/scene_view.h"
#include "sky/terrain_pass.h"

namespace firmament {

// How the sky's in-scattering reaches the pixels.
enum class SkyMethod {
  SkyViewLut,  // march a 192x108 sky-view table per frame, read it per pixel (Hillaire 2020)
  PerPixel,    // march every pixel (slower; used automatically for cameras above the atmosphere)
};

// luts.spectralSamples = kSpectralSamplesAuto: three wavelengths while the sun is high, 12 when it is
// within 15 degrees of the horizon or below it (where three wavelengths' colour conversion fails:
// docs/bench.md), three always with clouds or the 4D tables.
inline constexpr int kSpectralSamplesAuto = 0;
inline constexpr double kSpectralSamplesAutoZenithDeg = 75.0;
int resolveSpectralSamples(int requested, double sunZenithRad, bool clouds, bool tables);

struct SkyRenderOptions {
  AtmosphereLutSettings luts{.spectralSamples = kSpectralSamplesAuto};
  // Auto: f_ms by day, Bruneton's 4D tables in twilight (render_plan.h's twilightTablesWeight).
  MultipleScattering multipleScattering = MultipleScattering::Auto;
  ScatteringTableSettings tables;  // BrunetonTables: orders (tables.scatteringOrders), sizes
  // Auto's twilight tables (decision 0158): Bruneton's 4 orders at a quarter of the default size, one set
  // per spectral batch, computed once per atmosphere (the Sun's distance is not in their key) and cached.
  ScatteringTableSettings twilightTables = kTwilightTableSettings;
  FmsSkyIrradianceSettings fmsSkyIrradiance;  // HillaireFms: the ground's skylight table
  SkyMethod method = SkyMethod::SkyViewLut;   // HillaireFms: how the march reaches the pixels
  int viewSteps = 32;                         // march steps along each view ray (per pixel, or per sky-view texel)
  int skyViewWidth = 192;                     // azimuth samples
  int skyViewHeight = 108;                    // zenith samples
  gpu::DispatchOrder dispatchOrder = gpu::DispatchOrder::Auto;
  CloudOverrides clouds;  // march knobs over the scene's clouds quality preset
  // The aerial-perspective volume, for scenes whose clouds read it (aerial perspective "volume").
  AerialPerspectiveVolumeSettings aerialPerspective;
  CloudNoiseSettings cloudNoise;  // noise texture sizes (tests use small ones)
  // Replaces the scene's weather map (tests, tools); unset: sky/scene_weather.h decides.
  std::shared_ptr<const CloudWeatherMap> cloudWeather;
  // This frame continues the sequence of this renderer's previous render() (the same scene with the
  // camera, its orientation, the time or the sun moved): the clouds may reproject that frame
  // (/clouds/temporal_update, docs/clouds/resolution-and-temporal.md), and the sky-view table is kept
  // when its inputs are unchanged. False: a still, every pixel marched, every table of the frame computed.
  bool continueSequence = false;
  // This frame is a still on its own (`firmament render` without --frames; the API's stills: a Sky built
  // without temporal reprojection that makes no sequence frames): the clouds' march runs
  // /clouds/march/still_samples times with moved blue-noise offsets and is averaged. False: one march,
  // unless clouds.stillSamples is set, which then applies to every frame.
  bool still = false;
  // False: the frame stays on the GPU and RenderResult::image and ::clouds are empty. Benches time
  // renders this way: downloading two 1920x1080 float images per frame kept an H100 busy 13-37 % of
  // the time, and its driver lowered the clocks from 1980 to 615 MHz in about 2 s (docs/gpu.md).
  bool downloadImages = true;
  NightOptions night;          // the Moon, stars and the sky's own light (sky/night_plan.h)
  TerrainPassOptions terrain;  // the terrain pass's knobs (sky/terrain_pass.h)
};

// The plan options that follow from the render options (what `render --explain` prints).
PlanOptions planOptions(const SkyRenderOptions& options);

struct RenderResult {
  Image image;
  RenderPlan plan;
  SceneView view;
  std::vector<gpu::PassTiming> timings;  // GPU time per pass (ms), in execution order
  double frameMilliseconds = 0.0;        // GPU time of the per-frame passes
  double precomputeMilliseconds = 0.0;   // GPU time of the tables (0 when cached)
  bool tablesReused = false;             // from memory or the disk cache
  bool skyViewReused = false;            // a sequence's frame kept the previous frame's sky-view table (same inputs)
  std::string tablesSource;              // atmosphere tables: "memory", "disk cache" or "computed"
  std::string cloudNoiseSource;  // cloud noise textures: "memory", "disk cache" or "baked"; empty without clouds
  SkyMethod methodUsed = SkyMethod::SkyViewLut;
  int spectralSamples = 3;    // the wavelengths used (kSpectralSamplesAuto resolved)
  double tablesWeight = 0.0;  // the 4D tables' share of the clear sky (render_plan.h's sceneTablesWeight)
  std::string timingNote;     // non-empty when timings are wall clock
  // Scenes with clouds: rgb = the clouds' light in front of the sky, a = their transmittance (the image
  // is sky * a + rgb). Empty without clouds (and, like image, with SkyRenderOptions::downloadImages off).
  Image clouds;
  CloudSampleCounts cloudSamples;  // density evaluations per pixel of the cloud march
  bool cloudsReprojected = false;  // the clouds marched 1 in /clouds/temporal_update pixels, reprojected the rest
  NightDecision night;             // which night passes ran (sky/night_plan.h)
  // The clouds', terrain's and aerial perspective's light (sky/frame_light.h): the Sun, or the Moon when
  // it gives more ground illuminance. Chosen only for night frames with clouds or terrain.
  FrameLight light;
};

// Embedded mode (include/firmament/embed.h, docs/api.md): one frame's targets, the host's. colour: a
// storage view of an RGBA16F or RGBA32F image in VK_IMAGE_LAYOUT_GENERAL (read where the host drew, then
// written everywhere); depth: a sampled view (depth aspect) of the host's depth buffer in depthLayout, a
// perspective projection with the scene camera's orientation and horizontal field of view.
struct EmbeddedRecording {
  VkCommandBuffer commands = VK_NULL_HANDLE;  // recording; submitted by the host
  VkImageView colour = VK_NULL_HANDLE;
  bool colourHalf = true;  // RGBA16F (else RGBA32F)
  VkImageView depth = VK_NULL_HANDLE;
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  double near_m = 0.1;
  double far_m = 1.0e5;
  bool reversedDepth = false;
};

// What a host's shader needs to read the atmosphere like Firmament (include/firmament/atmosphere_lookup.glsl),
// as of the last record(): the views stay valid until the next record().
struct EmbeddedLookups {
  const gpu::Image* transmittance = nullptr;
  const gpu::Image* aerialPerspective = nullptr;
  float parameters[4][4] = {};  // FirmamentAtmosphere: radii, sun, sunIlluminance, image
};

class SkyRenderer {
 public:
  explicit SkyRenderer(gpu::Context& context);
  RenderResult render(const Scene& scene, const SkyRenderOptions& options = {});
  // Embedded mode: the frame's passes recorded into targets.commands (not submitted), composited with
  // the host's depth and written to its colour image. Preparation (tables, cloud noise, a new weather
  // map, first-use resources) is submitted to the context's queue and waited for here, before anything
  // is recorded; a frame needing none submits nothing (Context::submissionCount). Three wavelengths
  // (one spectral batch) always. The resources the recording uses stay until the next record().
  // result.timings and frameMilliseconds are the previous record()'s passes (timestamps in the host's
  // command buffer, read without waiting; empty when they are not available).
  RenderResult record(const Scene& scene, const SkyRenderOptions& options, const EmbeddedRecording& targets);
  const EmbeddedLookups& lookups() const { return lookups_; }
  gpu::Context& context() { return context_; }
  // The clouds' Beer shadow map of the last render with it enabled (RGBA floats; empty otherwise).
  std::vector<float> cloudShadowMap() const;
  // The terrain pass of the last render with terrain (its depth and hits), null before one.
  const TerrainPass* terrainPass() const { return terrain_.get(); }

 private:
  // render() in four steps: plan (the view, the options' automatic choices, the passes), prepare (the
  // tables and the clouds' weather and noise, each in its own submission and reused while unchanged),
  // record (the sky, then the clouds, into one command list) and resolve (submit, timings, downloads).
  struct Frame;
  Frame plan(const Scene& scene, const SkyRenderOptions& options, RenderResult& result);
  void prepareTables(Frame& frame, RenderResult& result);
  void prepareClouds(const Scene& scene, Frame& frame, RenderResult& result);
  void recordSky(Frame& frame, RenderResult& result, gpu::CommandList& commands);
  void recordNight(const Scene& scene, Frame& frame, RenderResult& result, gpu::CommandList& commands);
  void recordDayMoonDisc(const Scene& scene, Frame& frame, RenderResult& result, gpu::CommandList& commands);
  void recordClouds(Frame& frame, RenderResult& result, gpu::CommandList& commands);
  // recordSky, recordNight, chooseLight and, without clouds, recordTerrain: the steps before the clouds.
  void recordBeforeClouds(const Scene& scene, Frame& frame, RenderResult& result, gpu::CommandList& commands);
  // The light of the clouds and terrain at night (sky/frame_light.h), its blocks uploaded.
  void chooseLight(Frame& frame, RenderResult& result);
  // The terrain (sky/terrain_pass.h) over the sky, before the clouds; shadow: the clouds' Beer shadow map.
  void recordTerrain(Frame& frame, RenderResult& result, gpu::CommandList& commands, const TerrainCloudShadow* shadow);
  void resolve(const Scene& scene, Frame& frame, gpu::CommandList& commands, RenderResult& result);
  // Embedded mode: the aerial-perspective volume for the host's pixels (unless the clouds recorded one),
  // then the host's depth and colour into the frame (sky/embed_composite.glsl, mode 0), or, without
  // clouds, straight to the host's image (mode 2).
  void recordHostDepth(Frame& frame, RenderResult& result, gpu::CommandList& commands, bool aerialRecorded);
  void recordHostWrite(Frame& frame, gpu::CommandList& commands);  // mode 1: the frame to the host's image

  gpu::Context& context_;
  AtmosphereLuts luts_;
  std::vector<std::unique_ptr<FmsSkyIrradiance>> fmsSkyIrradiance_;  // one per spectral batch
  // The 4D tables, one per spectral batch (created on first use, 5 pipelines each).
  std::vector<std::unique_ptr<ScatteringTables>> tables_;
  gpu::ComputePipeline skyViewPipeline_;
  gpu::ComputePipeline skyPipeline_;                        // sky/render_sky: the sky-view table read
  std::unique_ptr<gpu::ComputePipeline> skyMarchPipeline_;  // sky/render_sky_march: a march per pixel
  std::unique_ptr<gpu::ComputePipeline> skyTablesPipeline_;
  std::unique_ptr<CloudPass> clouds_;                          // created for the first scene with clouds
  std::unique_ptr<gpu::ComputePipeline> lightShaftsPipeline_;  // sky/cloud_light_shafts
  std::unique_ptr<AerialPerspectiveVolume> aerial_;            // created for the first scene that reads it
  std::unique_ptr<TerrainPass> terrain_;                       // created for the first scene with terrain
  std::unique_ptr<NightPass> night_;                           // created for the first night scene
  std::unique_ptr<DayMoonDiscPass> dayMoon_;                   // created for the first daytime Moon in view
  gpu::Buffer frameBlock_;
  gpu::Buffer lightFrameBlock_;           // the frame block with the light's direction (light shafts under the Moon)
  std::vector<gpu::Buffer> lightBlocks_;  // per batch, the atmosphere block of the Moon as the light
  gpu::Image skyView_;
  // What skyView_ holds: the tables' key, the camera radius, the sun's zenith cosine, the steps (empty:
  // nothing). The table is in the sun's frame, so a camera that only turns keeps it.
  std::string skyViewKey_;
  // Embedded mode: the frame and the host's distances kept past record() (the host runs them later).
  std::shared_ptr<gpu::Buffer> embeddedOutput_;
  std::unique_ptr<gpu::CommandList> embeddedCommands_;  // the last record()'s, for its timestamps
  gpu::Buffer hostDistance_;
  gpu::Buffer farPlaceholder_;                               // one float, 1e30: no terrain
  std::unique_ptr<gpu::ComputePipeline> embedPipelines_[2];  // RGBA16F, RGBA32F host image
  std::unique_ptr<gpu::Sampler> nearestClamp_;
  double embeddedAerialDistance_m_ = 0.0;
  EmbeddedLookups lookups_;
};

}  // namespace firmament
