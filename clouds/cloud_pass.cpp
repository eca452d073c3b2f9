#include "clouds/cloud_pass.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace firmament {
namespace {

constexpr int kMaxLayers = 8;

// Every knob of shaders/clouds/cloud_march_knobs.def as a float, in the table's order: the march reads
// cloud.knobs.NAME (shaders/clouds/cloud_sampling.glsl declares the same struct from the same table; std140
// packs consecutive floats 4 to a vec4, the struct rounded up to 16 bytes).
struct alignas(16) CloudKnobsBlock {
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) float name;
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
};
constexpr int kCloudKnobCount = 0
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) +1
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
    ;
static_assert(sizeof(CloudKnobsBlock) == size_t((kCloudKnobCount + 3) / 4) * 16);
float knobFloat(double v) { return float(v); }
float knobFloat(AerialPerspective v) { return float(int(v)); }

// std140 mirror of CloudBlock in shaders/clouds/cloud_sampling.glsl.
struct CloudBlock {
  float cameraPosition[4];
  float cameraForward[4];  // w = fov
  float cameraRight[4];    // w = yaw
  float cameraUp[4];
  float sunDirection[4];   // w = largest march distance
  int32_t image[4];        // width, height, projection, layer count
  int32_t steps[4];        // view steps, light steps, octaves, flags
  float phaseLight[4];     // second phase lobe's Draine alpha, δ-scaled share f (0: none), unused, light march length
  float phase[4];          // g forward, g back, back weight, albedo
  float march[4];          // ambient bottom visibility, unused, coarse factor, unused (knobs: early exit, cone)
  float stepGrowth[4];     // base step h0 (m), growth start D (m), largest step factor G, unused (knobs: margin)
  float weatherRegion[4];  // width, height (m), skew east, north (m/m)
  float weatherPlanet[4];  // ground radius (m), low-transmittance step start T1 and largest factor K, other layers'
                           // light-step scale
  float shadowCentre[4];   // centre (cloud frame, m), extent (m)
  float shadowAxisU[4];    // axis u, start distance L (m)
  float shadowAxisV[4];    // axis v, march length (m)
  int32_t shadowSize[4];   // texels, steps, enabled, unused
  float aerial[4];  // the aerial-perspective volume's maximum distance (m), air-march steps, noise LOD scale, unused
  float layers[kMaxLayers * 5][4];
  float layerLighting[kMaxLayers]
                     [4];  // the diffusion floor's weight d, the reflected light's r and a_r, the base's limb darkening
  float weatherReach[4];   // the reach map's radius (m; 0: none, the margin test), the longest coarse span on it (m),
                           // unused x2
  float otherLayerMap[4];  // the other layers' map: log-warp scale ln(1 + E / rho0), rho0 (m), texels per side, tiles
                           // (0: none)
  float otherLayerOrigin[4];  // its plane's origin (cloud frame, m); w = the first row this bake writes
  float otherLayerAxisU[4];   // its axis u; w = the bake writes every w-th row from there
  float otherLayerAxisV[4];   // its axis v
  float otherLayerSun[4];     // the sun direction its lines follow
  float columnMap[4];  // the column map: log-warp scale ln(1 + E / rho0), rho0 (m), texels per side, levels K (0: none)
  float columnOrigin[4];   // its unit normal c; w = the first row this bake writes
  float columnAxisU[4];    // its axis u; w = the bake writes every w-th row from there
  float columnAxisV[4];    // its axis v; w = the planet radius R (m)
  float deepShadowMap[4];  // the deep shadow map (the other layers' map's placement): texels per side, levels K, near
                           // steps, baked (0: none)
  float buildUp[4];  // the higher orders' build-up along the view: k (0: off); the ambient as a slab (1) or by height
                     // (0); the slab through the other layers, baked this frame (1); the flow's scale
  float layerLowSun[kMaxLayers / 4]
                   [4];   // per layer (4 a vec4): the octaves' and the reflected light's low-sun scale's mu_0 (0: off)
  CloudKnobsBlock knobs;  // every knob, by name (the table)
};
static_assert(sizeof(CloudBlock) == (30 + kMaxLayers / 4 + kMaxLayers * 6) * 16 + sizeof(CloudKnobsBlock));

// The per-frame maps (the other layers' map, clouds/other_layer_map.glsl; the column map,
// clouds/column_map.glsl; the deep shadow map, clouds/deep_shadow_map.glsl). Their log warp's rho0: the distance from
// the map's origin within which texels shrink no further (clouds/log_warp.glsl: a texel's side is (|a| + rho0) ln(1 + E
// / rho0) 2 / N).
constexpr double kMapRho0_m = 1000.0;
// In a sequence the maps are re-baked one in w of their rows per frame (interleaved), so a texel is at
// most w frames old, while the clouds' drift over those frames stays under kMapDrift_m, the sun within
// kMapSunMove_rad of the maps' (a sun line's crossing ~10 km away moves ~1 m) and the camera within
// kMapCameraMove_m of their origin (the extent E is the march's reach plus that); otherwise, and for
// every still, all of them. w is the largest of kMapRowStrides that keeps the drift under the bound
// (10 m/s of wind at 30 frames per second, 0.33 m a frame: 16), and a change of w re-bakes all rows.
// The bound, 8 m, is under a quarter of the smallest texel (34 m at the maps' origin, 256 texels).
constexpr int kMapRowStrides[3] = {16, 8, 4};
constexpr double kMapDrift_m = 8.0;
constexpr double kMapSunMove_rad = 1e-4;
constexpr double kMapCameraMove_m = 1000.0;

// The log warp's scale ln(1 + E / rho0) for a map reaching E = the march's reach + kMapCameraMove_m
// (clouds/log_warp.glsl; once per frame here rather than per lookup).
double mapLogWarpScale(const CloudMarchSettings& m) {
  return std::log(1.0 + (m.maxDistance_m + kMapCameraMove_m) / kMapRho0_m);
}

// Whether this frame bakes the column map (clouds/column_map.glsl): the octaves' way from the top and
// the diffusion floor need the vertical optical depths only with more than one octave.
bool usesColumnMap(const CloudSettings& settings) { return settings.march.columnMap && settings.lighting.octaves > 1; }
// The ambient's view of the other layers (bake_column_ambient.comp): more than one layer, the ambient on
// as a slab that looks through them.
bool usesColumnAmbient(const CloudSettings& settings) {
  const CloudMarchSettings& m = settings.march;
  return usesColumnMap(settings) && settings.layers.size() > 1 && m.ambient && m.ambientSlab &&
         m.ambientThroughOtherLayers;
}

// Whether this frame bakes the other layers' map: light through the other layers, from the map, with
// more than one layer.
bool usesOtherLayerMap(const CloudSettings& settings) {
  const CloudMarchSettings& m = settings.march;
  return m.lightThroughOtherLayers && m.otherLayerMap && settings.layers.size() > 1;
}

// Whether this frame bakes the deep shadow map: on, the light march runs to the layer's exit (the map
// holds the way to the top), and it keeps fewer steps than it may take (lightStepsForLength: up to 4
// lightSteps).
bool usesDeepShadowMap(const CloudSettings& settings) {
  const CloudMarchSettings& m = settings.march;
  return m.deepShadowMap && m.lightMarchToExit && m.deepShadowNearSteps < 4 * std::max(m.lightSteps, 1);
}

// Whether this frame bakes any of the per-frame maps (they share a placement).
bool usesMaps(const CloudSettings& settings) {
  return usesOtherLayerMap(settings) || usesColumnMap(settings) || usesDeepShadowMap(settings);
}

struct Push {
  gpu::TileDispatch tiles;
  int32_t firstBatch;
  int32_t divisor;    // the march's grid is 1/divisor of the image in x and y
  int32_t composite;  // 1: the march composites over the sky; 0: clouds/upsample_clouds or temporal_resolve does
  int32_t noiseShift;
  float pointOffset[2];  // grid pixel p marches image point divisor p + pointOffset
  float pad[2];
};

// std140 mirror of TemporalBlock in shaders/clouds/temporal_resolve.comp.
struct TemporalBlock {
  float cameraPosition[4];
  float cameraForward[4];
  float cameraRight[4];
  float cameraUp[4];
  int32_t image[4];
  float previousPosition[4];
  float previousForward[4];
  float previousRight[4];
  float previousUp[4];
  int32_t previousImage[4];
  float motion[4];
};
static_assert(sizeof(TemporalBlock) == 11 * 16);

struct NeighbourhoodPush {
  gpu::TileDispatch tiles;  // the march's grid
  int32_t offset[2];
  int32_t k;
  int32_t pad;
};

struct ResolvePush {
  gpu::TileDispatch tiles;  // the image
  int32_t gridWidth;
  int32_t gridHeight;
  int32_t k;
  int32_t clampHistory;
  int32_t offset[2];
};

// The order in which a k x k block's pixels are marched over k^2 frames: the Bayer matrix's (each
// next pixel far from the ones just marched). kBayer4[n] = (x, y) of the n-th frame's pixel.
constexpr int kBayer2[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
constexpr int kBayer4[16][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};

uint64_t fnv1a(const void* data, size_t bytes, uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

struct UpsamplePush {
  gpu::TileDispatch tiles;  // the image
  int32_t coarseWidth;
  int32_t coarseHeight;
  int32_t divisor;
  int32_t pad;
};

void put(float (&out)[4], double x, double y, double z, double w) {
  out[0] = float(x), out[1] = float(y), out[2] = float(z), out[3] = float(w);
}
void put(float (&out)[4], const glm::dvec3& v, double w = 0.0) { put(out, v.x, v.y, v.z, w); }

// A unit axis perpendicular to the unit vector d (the second is cross(d, axis)): the maps' placements.
glm::dvec3 perpendicularAxis(const glm::dvec3& d) {
  return glm::normalize(std::abs(d.z) < 0.9 ? glm::cross(d, glm::dvec3(0.0, 0.0, 1.0))
                                            : glm::cross(d, glm::dvec3(1.0, 0.0, 0.0)));
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
      block_(context, sizeof(CloudBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host, "cloud block"),
      counters_(context, 3 * sizeof(uint32_t), gpu::BufferUsage::Storage, gpu::MemoryLocation::Host, "cloud counters"),
      temporalBlock_(context, sizeof(TemporalBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host,
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

namespace {
// Whether a weather map evolved from `before` by no more than the reprojection's clamp absorbs: the
// clouds of a weather scene's 30 fps sequence (the map simulated to each frame's time) change by
// ~1e-4 in coverage per frame, a time-lapse's by far more. The same size and region, the skew within
// 1e-3 m per m (1 m at 1 km), coverage and type within 0.01 and the top within 10 m in every texel
// (precipitation is not read).
bool weatherEvolvedLittle(const std::vector<float>& before, glm::dvec4 regionBefore, const std::vector<float>& now,
                          glm::dvec4 region) {
  if (before.size() != now.size() || regionBefore.x != region.x || regionBefore.y != region.y ||
      std::abs(regionBefore.z - region.z) > 1e-3 || std::abs(regionBefore.w - region.w) > 1e-3)
    return false;
  for (size_t i = 0; i + 3 < now.size(); i += 4)
    if (std::abs(now[i] - before[i]) > 0.01f || std::abs(now[i + 1] - before[i + 1]) > 0.01f ||
        std::abs(now[i + 3] - before[i + 3]) > 10.0f)
      return false;
  return true;
}
}  // namespace

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

std::vector<uint8_t> CloudPass::uploadBlock(const CloudSettings& settings, const CloudView& view,
                                            const AtmosphereLuts& luts, double aerialDistance_m) {
  const auto layers = sharedCloudLayers(settings, luts.parameters().bottom_radius);
  const CloudMarchSettings& m = settings.march;
  const CloudLightingSettings& l = settings.lighting;
  CloudBlock b{};
  put(b.cameraPosition, view.cameraPosition);
  put(b.cameraForward, view.camera.forward, view.camera.fov);
  put(b.cameraRight, view.camera.right, view.camera.yaw);
  put(b.cameraUp, view.camera.up);
  put(b.sunDirection, view.sunDirection, m.maxDistance_m);
  b.image[0] = view.camera.width;
  b.image[1] = view.camera.height;
  b.image[2] = view.camera.projection;
  b.image[3] = int32_t(layers.size());
  b.steps[0] = std::max(m.viewSteps, 1);
  b.steps[1] = std::max(m.lightSteps, 1);
  b.steps[2] = std::clamp(l.octaves, 1, 8);
  b.steps[3] = (m.jitter ? 2 : 0) | (m.ambient ? 4 : 0) | (m.uniformSteps ? 8 : 0) | (m.lightMarchToExit ? 16 : 0) |
               (m.msZenithDepth ? 32 : 0) | (m.msScatteredOnly ? 64 : 0) | (m.lightStepsPerThickness ? 128 : 0) |
               (m.lightThroughOtherLayers ? 256 : 0) | (m.earlyExitRemainder ? 512 : 0) |
               (m.reflectedLowSunDepth ? 1024 : 0);
  // Growing steps (common/cloud_march.glsl): h0 = H / N, growth from D = H, cap G.
  const double thickest = cloudThickestLayer(settings);
  put(b.stepGrowth, thickest / double(b.steps[0]), thickest, std::max(m.maxStepFactor, 1.0), 0.0);
  // a <= b is enforced when the scene is read; clamp again for settings built in code.
  // a, b, c are per layer (below).
  put(b.phaseLight, l.alpha, m.deltaScaling ? cloudPhaseDeltaFraction(l) : 0.0, 0.0,
      m.lightMarchToExit ? m.lightMaxLength_m : cloudLightMarchLength(settings));
  put(b.phase, l.gForward, l.gBack, l.backWeight, l.albedo);
  put(b.march, l.ambientBottomVisibility, 0.0, double(std::max(m.coarseFactor, 1)), 0.0);
  for (size_t i = 0; i < layers.size(); ++i) {
    const shared::CloudLayer& c = layers[i];
    put(b.layers[5 * i], c.bottom_radius, c.top_radius, c.coverage, c.extinction);
    put(b.layers[5 * i + 1], c.density_scale, c.anvil, c.shape_period, c.detail_period);
    // The w components: the layer's octave parameters a (<= b, enforced when the scene is read; clamped
    // again for settings built in code), b, c.
    const CloudLayerSettings& ls = settings.layers[i];
    put(b.layers[5 * i + 2], c.detail_strength, c.curl_period, c.curl_strength, std::min(ls.msA, ls.msB));
    put(b.layers[5 * i + 3], c.wind_offset, ls.msB);
    put(b.layers[5 * i + 4], c.skew.x, c.skew.y, double(c.kind), ls.msC);
    put(b.layerLighting[i], ls.msD, ls.msR, ls.msRA, cloudTypeBaseLimbDarkening(ls.kind));
  }
  if (!weatherImage_) throw std::logic_error("CloudPass: setWeatherMap before record");
  put(b.weatherRegion, weatherRegion_.x, weatherRegion_.y, weatherRegion_.z, weatherRegion_.w);
  // The longest coarse span on a reach map: a span's points lie within span (1 + |skew|) of each other
  // on the map (the skew shifts the columns with height); 0.9 leaves room for the map's tangent-plane
  // placement.
  put(b.weatherReach, reachRadius_,
      0.9 * reachRadius_ / (1.0 + glm::length(glm::dvec2(weatherRegion_.z, weatherRegion_.w))), 0.0, 0.0);
  put(b.weatherPlanet, luts.parameters().bottom_radius, std::max(m.lowTransmittanceStepStart, 0.0),
      std::max(m.lowTransmittanceStepMax, 1.0), std::max(m.otherLayerLightStepsScale, 0.0));
  // Beer shadow map placement (common/cloud_shadow.glsl): centred above the camera's ground point at
  // the layers' mid-height, axes perpendicular to the sun; the march starts L above C along the sun,
  // L = (top - mid) / max(mu_s, 0.05) + 1 km + the square's half diagonal x tan(theta_s) (past every
  // layer's top over the square for any sun above the horizon), and runs at most 2 L.
  {
    const double ground = luts.parameters().bottom_radius;
    double lowest = 1e30, highest = 0.0;
    for (const auto& l : settings.layers) lowest = std::min(lowest, l.bottom_m), highest = std::max(highest, l.top_m);
    const double mid = 0.5 * (lowest + highest);
    const glm::dvec3 centre(0.0, 0.0, ground + mid);
    const glm::dvec3 sun = glm::normalize(view.sunDirection);
    const glm::dvec3 u = perpendicularAxis(sun);
    const glm::dvec3 v = glm::cross(sun, u);
    // L also allows for the square's extent: a texel at distance e from the centre along the sun's
    // azimuth meets the layers e tan(theta_s) deeper or shallower along the sun, so with the half
    // diagonal e = extent / sqrt(2) the start plane lies sunward of every layer over the square (the
    // bake marches only each texel's stretch inside the layers, so a long march costs no resolution).
    const double muS = std::max(sun.z, 0.05);
    const double tanS = std::sqrt(std::max(1.0 - muS * muS, 0.0)) / muS;
    const double start = (highest - mid) / muS + 1000.0 + m.shadowMapExtent / std::sqrt(2.0) * tanS;
    put(b.shadowCentre, centre, m.shadowMapExtent);
    put(b.shadowAxisU, u, start);
    put(b.shadowAxisV, v, 2.0 * start);
    shadowPlacement_ = {centre, u, v, m.shadowMapExtent, start};
    b.shadowSize[0] = std::max(m.shadowMapSize, 1);
    b.shadowSize[1] = std::max(m.shadowMapSteps, 1);
    b.shadowSize[2] = m.beerShadowMap ? 1 : 0;
  }
  put(b.otherLayerMap, mapLogWarpScale(m), kMapRho0_m, double(std::max(m.otherLayerMapSize, 1)),
      usesOtherLayerMap(settings) ? double((layers.size() + 3) / 4) : 0.0);
  put(b.otherLayerOrigin, maps_.origin, double(maps_.firstRow));
  put(b.otherLayerAxisU, maps_.u, double(maps_.rowStride));
  put(b.otherLayerAxisV, maps_.v);
  put(b.otherLayerSun, maps_.sun);
  put(b.columnMap, mapLogWarpScale(m), kMapRho0_m, double(std::max(m.columnMapSize, 1)),
      usesColumnMap(settings) ? double(std::max(m.columnMapLevels, 1)) : 0.0);
  put(b.columnOrigin, maps_.column, double(maps_.firstRow));
  put(b.columnAxisU, maps_.columnU, double(maps_.rowStride));
  put(b.columnAxisV, maps_.columnV, luts.parameters().bottom_radius);
  put(b.deepShadowMap, double(std::max(m.deepShadowMapSize, 1)), double(std::max(m.deepShadowMapLevels, 1)),
      double(std::max(m.deepShadowNearSteps, 0)), usesDeepShadowMap(settings) ? 1.0 : 0.0);
  // z: whether this frame bakes the column map's ambient slices (one layer, or the column map off: none,
  // and the march must not read them).
  put(b.buildUp, std::max(m.msBuildUpScale, 0.0), m.ambientSlab ? 1.0 : 0.0, usesColumnAmbient(settings) ? 1.0 : 0.0,
      std::max(m.ambientFlow, 0.0));
  for (size_t i = 0; i < layers.size(); ++i)
    b.layerLowSun[i / 4][i % 4] =
        float(std::clamp(m.octaveLowSunMu >= 0.0 ? m.octaveLowSunMu : settings.layers[i].msLowSunMu, 0.0, 1.0));
  put(b.aerial, aerialDistance_m, double(std::max(m.aerialPerspectiveSteps, 1)), std::max(m.noiseLodScale, 0.0), 0.0);
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) b.knobs.name = knobFloat(m.name);
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
  block_.upload(&b, sizeof(b));
  // The history's key: the block without what reprojection follows (camera, sun, wind offset).
  std::vector<uint8_t> settingsKey;
  {
    CloudBlock k = b;
    std::fill(std::begin(k.cameraPosition), std::end(k.cameraPosition), 0.0f);
    std::fill(std::begin(k.cameraForward), std::end(k.cameraForward), 0.0f);
    std::fill(std::begin(k.cameraRight), std::end(k.cameraRight), 0.0f);
    std::fill(std::begin(k.cameraUp), std::end(k.cameraUp), 0.0f);
    std::fill(k.sunDirection, k.sunDirection + 3, 0.0f);
    std::fill(std::begin(k.shadowAxisU), std::end(k.shadowAxisU), 0.0f);
    std::fill(std::begin(k.shadowAxisV), std::end(k.shadowAxisV), 0.0f);
    std::fill(std::begin(k.otherLayerOrigin), std::end(k.otherLayerOrigin), 0.0f);
    std::fill(std::begin(k.otherLayerAxisU), std::end(k.otherLayerAxisU), 0.0f);
    std::fill(std::begin(k.otherLayerAxisV), std::end(k.otherLayerAxisV), 0.0f);
    std::fill(std::begin(k.otherLayerSun), std::end(k.otherLayerSun), 0.0f);
    std::fill(std::begin(k.columnOrigin), std::end(k.columnOrigin), 0.0f);
    std::fill(std::begin(k.columnAxisU), std::end(k.columnAxisU), 0.0f);
    std::fill(std::begin(k.columnAxisV), std::end(k.columnAxisV), 0.0f);
    for (size_t i = 0; i < layers.size(); ++i) std::fill(k.layers[5 * i + 3], k.layers[5 * i + 3] + 3, 0.0f);
    const auto* bytes = reinterpret_cast<const uint8_t*>(&k);
    settingsKey.assign(bytes, bytes + sizeof(k));
  }
  return settingsKey;
}

void CloudPass::allocateShadowImage(const CloudMarchSettings& m) {
  const uint32_t shadowSize = m.beerShadowMap ? uint32_t(std::max(m.shadowMapSize, 1)) : 1u;
  if (!shadowImage_ || shadowImage_.width() != shadowSize)
    shadowImage_ =
        gpu::Image(context_, {shadowSize, shadowSize, 1, gpu::Format::RGBA32F, true, true, "cloud shadow map"});
}

void CloudPass::bindBake(gpu::ComputePipeline& pipeline, const gpu::Image& target, const AtmosphereLuts& luts,
                         const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                         gpu::CommandList& commands) {
  const AtmosphereLuts::Batch& lut = luts.batch(0);
  commands.bind(pipeline, {lightBlock(luts, 0),
                           {lut.transmittance, luts.linearClamp()},
                           {lut.multipleScattering, luts.linearClamp()},
                           {*skyIrradiance[0], luts.linearClamp()},
                           {noise_.shape(), noise_.linearRepeat()},
                           {noise_.detail(), noise_.linearRepeat()},
                           {noise_.curl(), noise_.linearRepeat()},
                           {noise_.blueNoise(), noise_.nearestRepeat()},
                           skyFrame,
                           cloudFrames_[current_],
                           block_,
                           counters_,
                           {weatherImage_, noise_.linearRepeat()},
                           target});
}

void CloudPass::recordBake(const AtmosphereLuts& luts, const std::vector<const gpu::Image*>& skyIrradiance,
                           gpu::Buffer& skyFrame, gpu::CommandList& commands) {
  const uint32_t shadowSize = shadowImage_.width();
  // The shadow bake and the march share their first 13 bindings; the bake's 14th is the shadow map it
  // writes, which the march reads, and the march has two more: the anisotropy table (its per-pixel
  // air march) and the aerial-perspective volume.
  bindBake(bakeShadow_, shadowImage_, luts, skyIrradiance, skyFrame, commands);
  const uint32_t groups = (shadowSize + 7) / 8;
  commands.dispatch(groups, groups, 1, "clouds/bake_shadow_map");
  commands.barrier();
}

void CloudPass::recordOtherLayerMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                                    const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                    gpu::CommandList& commands) {
  const bool bake = usesOtherLayerMap(settings);
  const int size = settings.march.otherLayerMapSize;
  if (bake && (size < 8 || size > 4096))
    throw InputError("clouds: other_layer_map_size " + std::to_string(size) + "; allowed: 8 to 4096 texels");
  const uint32_t width = bake ? uint32_t(size) : 1u;
  const uint32_t height = bake ? uint32_t(size) * uint32_t((settings.layers.size() + 3) / 4) : 1u;
  if (!otherLayerImage_ || otherLayerImage_.width() != width || otherLayerImage_.height() != height)
    otherLayerImage_ =
        gpu::Image(context_, {width, height, 1, gpu::Format::RGBA32F, true, true, "cloud other layers' map"});
  if (!bake) return;
  bindBake(bakeOtherLayers_, otherLayerImage_, luts, skyIrradiance, skyFrame, commands);
  const uint32_t rows = bakedRows(height);
  commands.dispatch((width + 7) / 8, (rows + 7) / 8, 1, "clouds/bake_other_layers");
  commands.barrier();
}

void CloudPass::recordLevelMap(gpu::ComputePipeline& pipeline, gpu::Image& image, bool bake, int size, int levels,
                               size_t layers, int extraSlices, const char* name, const char* pass,
                               const AtmosphereLuts& luts, const std::vector<const gpu::Image*>& skyIrradiance,
                               gpu::Buffer& skyFrame, gpu::CommandList& commands) {
  const uint32_t width = bake ? uint32_t(size) : 1u;
  const uint32_t depth = bake ? uint32_t(layers) * uint32_t(levels + 1) + uint32_t(extraSlices) : 2u;
  if (!image || image.width() != width || image.depth() != depth)
    image = gpu::Image(context_, {width, width, depth, gpu::Format::R32F, true, true, name});
  if (!bake) return;
  bindBake(pipeline, image, luts, skyIrradiance, skyFrame, commands);
  const uint32_t rows = bakedRows(width);
  commands.dispatch((width + 7) / 8, (rows + 7) / 8, uint32_t(layers), pass);
  commands.barrier();
}

void CloudPass::recordColumnMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                                const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                gpu::CommandList& commands) {
  const bool bake = usesColumnMap(settings);
  const int size = settings.march.columnMapSize, levels = settings.march.columnMapLevels;
  if (bake && (size < 8 || size > 4096))
    throw InputError("clouds: column_map_size " + std::to_string(size) + "; allowed: 8 to 4096 texels");
  if (bake && (levels < 1 || levels > 64))
    throw InputError("clouds: column_map_levels " + std::to_string(levels) + "; allowed: 1 to 64");
  // Two more slices per layer: the ambient's view of the other layers (bake_column_ambient.comp), baked
  // from the levels' whole columns where there are other layers and the ambient's slab looks through them.
  const size_t layers = settings.layers.size();
  recordLevelMap(bakeColumns_, columnImage_, bake, size, levels, layers, 2 * int(layers), "cloud column map",
                 "clouds/bake_columns", luts, skyIrradiance, skyFrame, commands);
  if (bake && usesColumnAmbient(settings)) {
    bindBake(bakeColumnAmbient_, columnImage_, luts, skyIrradiance, skyFrame, commands);
    const uint32_t width = uint32_t(size);
    const uint32_t rows = bakedRows(width);
    commands.dispatch((width + 7) / 8, (rows + 7) / 8, uint32_t(layers), "clouds/bake_column_ambient");
    commands.barrier();
  }
}

void CloudPass::recordDeepShadowMap(const CloudSettings& settings, const AtmosphereLuts& luts,
                                    const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                    gpu::CommandList& commands) {
  const CloudMarchSettings& m = settings.march;
  const int size = m.deepShadowMapSize, levels = m.deepShadowMapLevels;
  if (m.deepShadowMap && (size < 8 || size > 4096))
    throw InputError("clouds: deep_shadow_map_size " + std::to_string(size) + "; allowed: 8 to 4096 texels");
  if (m.deepShadowMap && (levels < 1 || levels > 128))
    throw InputError("clouds: deep_shadow_map_levels " + std::to_string(levels) + "; allowed: 1 to 128");
  if (m.deepShadowMap && m.deepShadowNearSteps < 0)
    throw InputError("clouds: deep_shadow_near_steps " + std::to_string(m.deepShadowNearSteps) +
                     "; allowed: 0 or more");
  recordLevelMap(bakeDeepShadow_, deepShadowImage_, usesDeepShadowMap(settings), size, levels, settings.layers.size(),
                 0, "cloud deep shadow map", "clouds/bake_deep_shadow", luts, skyIrradiance, skyFrame, commands);
}

void CloudPass::recordShadowMap(const CloudSettings& settings, const CloudView& view, const AtmosphereLuts& luts,
                                const std::vector<const gpu::Image*>& skyIrradiance, gpu::Buffer& skyFrame,
                                double aerialDistance_m, gpu::CommandList& commands) {
  if (!settings.march.beerShadowMap) return;
  if (settings.layers.size() > size_t(kMaxLayers))
    throw InputError("clouds: at most " + std::to_string(kMaxLayers) + " layers");
  lightBlocks_ = view.lightBlocks;
  uploadBlock(settings, view, luts, aerialDistance_m);
  for (gpu::Buffer& frame : cloudFrames_)  // bound (unused) by the bake
    if (!frame || frame.size() != skyFrame.size())
      frame =
          gpu::Buffer(context_, skyFrame.size(), gpu::BufferUsage::Storage, gpu::MemoryLocation::Device, "cloud frame");
  allocateShadowImage(settings.march);
  recordBake(luts, skyIrradiance, skyFrame, commands);
  shadowBaked_ = true;
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

  // Temporal reprojection (clouds/temporal_resolve.comp): the march covers every k-th pixel of the
  // image in x and y, one pixel of each k x k block cycling over k^2 frames, when the previous frame
  // can be reprojected: same settings and weather, and the camera outside the layers (flying through a
  // cloud, the parallax inside the volume is not that of one depth per pixel: march everything), at
  // full resolution.
  const int update = m.temporalUpdate;
  if (update != 1 && update != 4 && update != 16)
    throw InputError("clouds: temporal_update " + std::to_string(update) + "; allowed: 1, 4, 16");
  const double cameraRadius = glm::length(view.cameraPosition);
  bool cameraInLayer = false;
  for (const shared::CloudLayer& c : layers) {
    const double margin = 0.05 * (c.top_radius - c.bottom_radius);
    cameraInLayer = cameraInLayer || (cameraRadius > c.bottom_radius - margin && cameraRadius < c.top_radius + margin);
  }
  const glm::dvec3 windOffset = layers.empty() ? glm::dvec3(0.0) : glm::dvec3(layers[0].wind_offset);
  // A reduced-resolution march (divisor > 1) runs every frame instead: it is already the cheap path.
  const int k = m.resolutionDivisor > 1 ? 1 : update == 16 ? 4 : update == 4 ? 2 : 1;
  // The same map, or one that evolved a little (a weather scene's sequence simulates it to each
  // frame's time): what changed the clamp takes out, as it does for the sun's move.
  const bool sameWeather =
      history_.weather == weatherHash_ ||
      weatherEvolvedLittle(history_.weatherTexels, history_.weatherRegion, weatherTexels_, weatherRegion_);
  reprojected_ =
      k > 1 && continueSequence && history_.usable && !cameraInLayer && history_.settings == settingsKey && sameWeather;
  // The per-frame maps: one in w of their rows when the frame continues one that baked them with the
  // same settings and the clouds, the sun and the camera moved little (kMapRowStrides); else all of
  // them, placed at the camera and the sun of this frame.
  if (usesMaps(settings)) {
    const glm::dvec3 sun = glm::normalize(view.sunDirection);
    const double sunMove = std::acos(std::clamp(glm::dot(sun, maps_.sun), -1.0, 1.0));
    const double drift = glm::length(windOffset - history_.windOffset);
    int stride = 0;
    for (int w : kMapRowStrides)
      if (stride == 0 && drift * w < kMapDrift_m) stride = w;
    const bool partial = continueSequence && maps_.baked && history_.settings == settingsKey && sameWeather &&
                         sunMove < kMapSunMove_rad &&
                         glm::length(view.cameraPosition - maps_.origin) < kMapCameraMove_m && stride > 0 &&
                         (maps_.rowStride == 1 || maps_.rowStride == stride);
    if (partial) {
      maps_.firstRow = (maps_.firstRow + 1) % stride;
      maps_.rowStride = stride;
    } else {
      maps_.origin = view.cameraPosition;
      maps_.sun = sun;
      maps_.u = perpendicularAxis(sun);
      maps_.v = glm::cross(sun, maps_.u);
      const glm::dvec3 c = glm::normalize(view.cameraPosition);
      maps_.column = c;
      maps_.columnU = perpendicularAxis(c);
      maps_.columnV = glm::cross(c, maps_.columnU);
      maps_.firstRow = 0;
      maps_.rowStride = 1;
    }
    uploadBlock(settings, view, luts, volume ? aerial->maxDistance_m : 0.0);
  }
  maps_.baked = usesMaps(settings);
  int offset[2] = {0, 0};
  if (reprojected_) {
    const int n = int(temporalFrame_ % uint32_t(k * k));
    offset[0] = k == 4 ? kBayer4[n][0] : kBayer2[n][0];
    offset[1] = k == 4 ? kBayer4[n][1] : kBayer2[n][1];
  }

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
    // The ray through the centre of the d x d pixels a grid pixel stands for, or this frame's pixel of
    // each block when reprojecting (with a new blue-noise pattern: each block pixel's 16 marches differ).
    Push push{marchTiles,
              batch == 0 ? 1 : 0,
              divisor,
              divisor == 1 ? 1 : 0,
              reprojected_ ? int32_t((temporalFrame_ * 37u) % 4096u) : 0,
              {reprojected_ ? float(offset[0]) + 0.5f : 0.5f * float(divisor),
               reprojected_ ? float(offset[1]) + 0.5f : 0.5f * float(divisor)},
              {0.0f, 0.0f}};
    commands.pushConstants(push);
    commands.dispatchTiles(marchTiles, "clouds/render_clouds");
    if (batch + 1 < luts.batchCount() || divisor > 1) commands.barrier();
  }
  if (reprojected_) {
    TemporalBlock t{};
    put(t.cameraPosition, view.cameraPosition);
    put(t.cameraForward, view.camera.forward, view.camera.fov);
    put(t.cameraRight, view.camera.right, view.camera.yaw);
    put(t.cameraUp, view.camera.up);
    t.image[0] = view.camera.width, t.image[1] = view.camera.height, t.image[2] = view.camera.projection;
    const CloudView& p = history_.view;
    put(t.previousPosition, p.cameraPosition);
    put(t.previousForward, p.camera.forward, p.camera.fov);
    put(t.previousRight, p.camera.right, p.camera.yaw);
    put(t.previousUp, p.camera.up);
    t.previousImage[0] = p.camera.width, t.previousImage[1] = p.camera.height, t.previousImage[2] = p.camera.projection;
    // The noise is read at p + wind offset: a feature at P now was at P + (offset now - offset then).
    // The clamp everywhere in proportion to the sun's move, fully from 0.25 degrees per frame (a
    // time-lapse; the day's course moves it ~1e-4 degrees per frame at 30 frames per second).
    const double sunMove =
        std::acos(std::clamp(glm::dot(glm::normalize(view.sunDirection), glm::normalize(p.sunDirection)), -1.0, 1.0));
    put(t.motion, windOffset - history_.windOffset, std::clamp(sunMove / (0.25 * shared::kPi / 180.0), 0.0, 1.0));
    temporalBlock_.upload(&t, sizeof(t));
    // The fresh neighbourhoods once per grid pixel, then the image (both timed as the resolve).
    const VkDeviceSize records = VkDeviceSize(coarseWidth) * coarseHeight * 3 * 4 * sizeof(float);
    if (!neighbourhoodRecords_ || neighbourhoodRecords_.size() < records)
      neighbourhoodRecords_ = gpu::Buffer(context_, records, gpu::BufferUsage::Storage, gpu::MemoryLocation::Device,
                                          "cloud neighbourhoods");
    // Bindings 3 and 4 are unused by the neighbourhood pass (its layout mirrors the resolve's numbering).
    commands.bind(neighbourhood_,
                  {coarseFrame_, depth_, neighbourhoodRecords_, historyFrame, skyFrame, temporalBlock_});
    NeighbourhoodPush neighbourhoodPush{marchTiles, {offset[0], offset[1]}, k, 0};
    commands.pushConstants(neighbourhoodPush);
    commands.dispatchTiles(marchTiles, "clouds/temporal_resolve");
    commands.barrier();
    commands.bind(resolve_,
                  {coarseFrame_, depth_, historyFrame, cloudFrame, skyFrame, temporalBlock_, neighbourhoodRecords_});
    ResolvePush push{tiles, int32_t(coarseWidth),    int32_t(coarseHeight),
                     k,     m.temporalClamp ? 1 : 0, {offset[0], offset[1]}};
    commands.pushConstants(push);
    commands.dispatchTiles(tiles, "clouds/temporal_resolve");
    ++temporalFrame_;
  } else if (divisor > 1) {
    commands.bind(upsample_, {coarseFrame_, cloudFrame, skyFrame});
    UpsamplePush push{tiles, int32_t(coarseWidth), int32_t(coarseHeight), divisor, 0};
    commands.pushConstants(push);
    commands.dispatchTiles(tiles, "clouds/upsample_clouds");
  }
  history_.usable = k > 1;
  history_.settings = std::move(settingsKey);
  if (history_.weather != weatherHash_) history_.weatherTexels = weatherTexels_;  // copied only when it changed
  history_.weather = weatherHash_;
  history_.weatherRegion = weatherRegion_;
  history_.view = view;
  history_.windOffset = windOffset;
}

}  // namespace firmament
