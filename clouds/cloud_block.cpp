// The cloud block: what the march and the bakes read of a frame's settings, packed for the GPU
// (std140; shaders/clouds/cloud_sampling.glsl declares the same block).
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

namespace {

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

// A layer in the block (std140: 5 vec4; shaders/clouds/cloud_sampling.glsl's CloudBlockLayer).
struct CloudBlockLayer {
  float bottomRadius, topRadius, coverage, extinction;
  float densityScale, anvil, shapePeriod, detailPeriod;
  float detailStrength, curlPeriod, curlStrength, msA;
  float windOffset[3], msB;
  float skew[2], kind, msC;
};
static_assert(sizeof(CloudBlockLayer) == 5 * 16 && offsetof(CloudBlockLayer, windOffset) == 48 &&
              offsetof(CloudBlockLayer, skew) == 64);
// A layer's lighting (one vec4; CloudBlockLayerLighting there).
struct CloudBlockLayerLighting {
  float floorWeight, reflectWeight, reflectDepthScale, baseLimb;
};
static_assert(sizeof(CloudBlockLayerLighting) == 16);

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
  CloudBlockLayer layers[kMaxLayers];
  CloudBlockLayerLighting layerLighting[kMaxLayers];
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
// The named layers keep the slots the march reads (std140 vec4 numbers 18 onward; the knobs after all).
static_assert(offsetof(CloudBlock, layers) == 18 * 16 &&
              offsetof(CloudBlock, layerLighting) == (18 + 5 * kMaxLayers) * 16);
static_assert(offsetof(CloudBlock, knobs) == (30 + kMaxLayers / 4 + kMaxLayers * 6) * 16);

}  // namespace

size_t cloud_pass_detail::cloudBlockBytes() { return sizeof(CloudBlock); }

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
    CloudBlockLayer& bl = b.layers[i];
    bl.bottomRadius = float(c.bottom_radius), bl.topRadius = float(c.top_radius), bl.coverage = float(c.coverage);
    bl.extinction = float(c.extinction);
    bl.densityScale = float(c.density_scale), bl.anvil = float(c.anvil), bl.shapePeriod = float(c.shape_period);
    bl.detailPeriod = float(c.detail_period);
    bl.detailStrength = float(c.detail_strength), bl.curlPeriod = float(c.curl_period);
    bl.curlStrength = float(c.curl_strength);
    bl.windOffset[0] = float(c.wind_offset.x), bl.windOffset[1] = float(c.wind_offset.y);
    bl.windOffset[2] = float(c.wind_offset.z);
    bl.skew[0] = float(c.skew.x), bl.skew[1] = float(c.skew.y), bl.kind = float(double(c.kind));
    // The layer's octave parameters a (<= b, enforced when the scene is read; clamped again for settings
    // built in code), b, c.
    const CloudLayerSettings& ls = settings.layers[i];
    bl.msA = float(std::min(ls.msA, ls.msB)), bl.msB = float(ls.msB), bl.msC = float(ls.msC);
    b.layerLighting[i] = {float(ls.msD), float(ls.msR), float(ls.msRA), float(cloudTypeBaseLimbDarkening(ls.kind))};
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
    for (size_t i = 0; i < layers.size(); ++i)
      std::fill(std::begin(k.layers[i].windOffset), std::end(k.layers[i].windOffset), 0.0f);
    const auto* bytes = reinterpret_cast<const uint8_t*>(&k);
    settingsKey.assign(bytes, bytes + sizeof(k));
  }
  return settingsKey;
}

}  // namespace firmament
