// Cloud layers over the clear sky (docs/clouds.md). Per pixel:
//  1. the view ray's stretches inside every layer's shell (common/cloud_density.glsl), in order;
//  2. a march of fine steps growing with the distance from the camera (common/cloud_march.glsl: the
//     base step is the thickest layer's thickness / `view steps`, growing in proportion to distance
//     beyond one thickness, capped), or, with the uniform flag, `view steps` equal steps spread over the
//     stretches' total length; blue-noise jitter; coarse steps of the shape-only density until it is
//     non-zero (empty-space skipping; exact, since the shape-only density bounds the full one); an
//     early exit at low transmittance. It alternates stepping to the next sample with cloud and
//     lighting it, so the lighting runs with most SIMD lanes busy (docs/clouds.md "Keeping SIMD lanes busy");
//  3. at every step with cloud: sunlight through the atmosphere (transmittance table at the sample)
//     and through the cloud (a light march of `light steps` along the sun), dual-lobe Henyey-Greenstein,
//     octave multiple scattering; ambient from the sky irradiance table and the ground; each step
//     integrated with Hillaire 2016's energy-conserving formula (cloudStepIntegral);
//  4. aerial perspective to the transmittance-weighted mean depth of the cloud: the air's
//     transmittance and in-scattering up to there, chosen at compile time (CLOUD_AERIAL_PERSPECTIVE;
//     lavapipe runs both sides of a branch on a uniform, docs/gpu.md):
//       2 (render_clouds.comp, default): read from the per-frame aerial-perspective volume
//         (sky/aerial_perspective_volume.comp; three trilinear fetches);
//       1 (render_clouds_ap_march.comp): a per-pixel march of `aerial steps` (default 8) of the
//         same clear-sky integrand (atmosphere/air_integrand.glsl);
//       0 (render_clouds_ap_off.comp): none (T_air = 1, no air light);
//  5. composite over the sky image: out = T_cloud * sky + L, with L = T_air L_cloud + (1 - T_cloud) L_air.
//     With a resolution divisor d > 1 the pixels are those of a grid d times coarser and only (L, T_cloud)
//     is written; clouds/upsample_clouds.comp interpolates it to the image and composites there.
// Radiance is carried at the batch's three wavelengths in two parts, light with the sun's spectrum and
// light with the sky's, converted to Rec.709 cd/m^2 with the atmosphere block's matrices.
#ifndef CLOUD_AERIAL_PERSPECTIVE
#error "define CLOUD_AERIAL_PERSPECTIVE (0 off, 1 march, 2 volume) before including clouds/render_clouds.glsl"
#endif
#include "atmosphere/aerial_perspective_sampling.glsl"
#include "atmosphere/air_integrand.glsl"
#include "atmosphere/atmosphere_sampling.glsl"
#include "atmosphere/irradiance_sampling.glsl"
#include "common/camera.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_lighting.glsl"
#include "common/cloud_march.glsl"
#include "common/cloud_weather.glsl"
#include "common/dispatch.glsl"
#include "clouds/cloud_sampling.glsl"
#include "common/cloud_shadow.glsl"
#include "clouds/other_layer_map.glsl"
#include "clouds/column_map.glsl"
#include "clouds/deep_shadow_map.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3) uniform sampler2D skyIrradianceLut;
layout(set = 0, binding = 7) uniform sampler2D blueNoise;    // read with texelFetch
// The frames (one vec4 per pixel, row-major; storage buffers, see sky/render_sky.comp):
layout(std430, set = 0, binding = 8) buffer SkyFrame { vec4 pixels[]; } skyFrame;      // read, composited, written
layout(std430, set = 0, binding = 9) buffer CloudFrame { vec4 pixels[]; } cloudFrame;  // rgb: cloud light L; a: T_cloud
// Sample counters (summed over the pixels by the first batch): view-march density evaluations (coarse
// and fine), light-march density evaluations, and the maps' bakes' (clouds/bake_other_layers,
// bake_columns).
layout(std430, set = 0, binding = 11) buffer CloudCounters { uint viewSamples; uint lightSamples; uint mapSamples; } counters;
// The cloud's depth per pixel of the march's grid (m along the ray): the transmittance-weighted mean
// depth where there is cloud, else where the ray enters the first shell (the march limit if none).
// Temporal reprojection (clouds/temporal_resolve.comp) moves each pixel's history with it.
layout(std430, set = 0, binding = 16) writeonly buffer CloudDepth { float depth[]; } cloudDepth;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  int firstBatch;  // 1: write (composite over the sky); 0: add this spectral batch's light
  int divisor;     // the march's grid is 1/divisor of the image's width and height (tiles: that grid)
  int composite;   // 1: composite over the sky frame here; 0: clouds/upsample_clouds or temporal_resolve does
  int noiseShift;  // added to the pixel for the blue-noise lookup (a new pattern per temporal frame)
  vec2 pointOffset;  // grid pixel p marches the image point divisor p + pointOffset (pixel units)
  // A still's sub-frames (CloudMarchSettings::stillSamples): the blue-noise value moved by jitterShift
  // (mod 1); (L, T) times sampleWeight, written at subFrame 0 and added after; the first batch
  // composites the sum over the sky at the last sub-frame (lastSubFrame 1).
  float jitterShift;
  float sampleWeight;
  int subFrame;
  int lastSubFrame;
} push;

const int kMaxSegments = 16;  // two stretches per layer, 8 layers

// The frame's features (clouds/cloud_pass.cpp, cloudMarchFeatures), a specialization constant: the
// code of an option the frame does not use is compiled out. lavapipe runs both sides of every branch
// under a mask and a loop's body at least once, so a single-layer frame without a shadow map still paid
// for the light through the other layers and the shadow-map lookup (docs/gpu.md). The runtime flags
// stay: a feature compiled in but switched off by them behaves as before. Default: everything.
layout(constant_id = 0) const uint kMarchFeatures = 0xffffffffu;
const bool kOtherLayers = (kMarchFeatures & 1u) != 0u;  // light through the other layers (flag 256, layers > 1)
const bool kShadowMap = (kMarchFeatures & 2u) != 0u;    // the Beer shadow map
const bool kWeatherReach = (kMarchFeatures & 4u) != 0u; // empty-space skipping by the coverage reach map
// 8 is free (the light samples by transmittance, decision 0002).
const bool kLightCone = (kMarchFeatures & 16u) != 0u;   // the light march's cone (the bench's first milestone)
const bool kSeveralLayers = (kMarchFeatures & 32u) != 0u;  // more than one layer (else layer 0 throughout)
const bool kOtherLayerMap = (kMarchFeatures & 64u) != 0u;     // the other layers' light from their map (when baked)
const bool kOtherLayerMarch = (kMarchFeatures & 128u) != 0u;  // the other layers' light by marching their crossings
const bool kColumnMap = (kMarchFeatures & 256u) != 0u;    // the vertical optical depths from the column map (when baked)
const bool kColumnMarch = (kMarchFeatures & 512u) != 0u;  // the vertical optical depths by marching up and down
const bool kDeepShadowMap = (kMarchFeatures & 1024u) != 0u;  // the own layer's far light from the deep shadow map (when baked)
const bool kReflection = (kMarchFeatures & 2048u) != 0u;  // the light the cloud behind a sample turns back (a layer's ms_r > 0)
const bool kReflectionMarch = (kMarchFeatures & 4096u) != 0u;  // its way behind a sample marched where the deep shadow map does not hold it
layout(set = 0, binding = 13) uniform sampler2D shadowMap;  // Beer shadow map, linear, clamp (when enabled)

layout(set = 0, binding = 14) uniform sampler2D multipleScatteringAnisotropy;  // the per-pixel air march
layout(set = 0, binding = 15) uniform sampler3D aerialVolume;  // the aerial-perspective volume (linear, clamp)
// The largest map coverage within cloud.weatherReach.x metres (clouds/cloud_weather_map.h
// coverageReach), for a map with sharp coverage (linear, repeat; 1x1 and unread otherwise).
layout(set = 0, binding = 17) uniform sampler2D weatherReachMap;
// The other layers' optical depth to the sun (clouds/other_layer_map.glsl; linear, clamp; 1x1 and unread
// without it).
layout(set = 0, binding = 18) uniform sampler2D otherLayerMap;
// Each layer's optical depth up and down from any point (clouds/column_map.glsl; linear, clamp; 1x1x1
// and unread without it).
layout(set = 0, binding = 19) uniform sampler3D columnMap;
// Each layer's optical depth along the sun from any point to its top (clouds/deep_shadow_map.glsl; linear,
// clamp; 1x1x1 and unread without it).
layout(set = 0, binding = 20) uniform sampler3D deepShadowMap;
// The distance to the terrain per image pixel (sky/terrain_pass.h; 1e30 where none), where the march
// stops (one float, unread, without terrain).
const bool kTerrainDepth = (kMarchFeatures & 8192u) != 0u;
layout(std430, set = 0, binding = 21) readonly buffer TerrainDepth { float t[]; } terrainDepth;

// Air between the camera and distance d along dir, by a march of `steps` equal steps of the clear-sky
// integrand (atmosphere/air_integrand.glsl, as the sky and the aerial-perspective volume): the
// in-scattered light in linear Rec.709 cd/m^2 (sky-like and sun-like parts converted) and the
// transmittance at the batch's wavelengths.
void airToDepth(AtmosphereParameters atmosphere, vec3 origin, vec3 dir, vec3 sun, float d, int steps, out vec3 light,
                out vec3 transmittance) {
  vec3 sky = vec3(0.0);
  vec3 sunlike = vec3(0.0);
  transmittance = vec3(1.0);
  float nu = dot(dir, sun);
  float phaseR = rayleighPhase(nu);
  float phaseM = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
  float dt = d / float(steps);
  for (int i = 0; i < steps; ++i) {
    vec3 p = origin + dir * ((float(i) + 0.5) * dt);
    AirSample air = airSampleAt(atmosphere, transmittanceLut, multipleScatteringLut, multipleScatteringAnisotropy, p, sun, dir,
                                phaseR, phaseM);
    accumulateAirStep(air, dt, sky, sunlike, transmittance);
  }
  light = skyRadianceToRgb() * sky + sunRadianceToRgb() * sunlike;
}

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  ivec2 pixel = ivec2(tiled);
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera = cameraFromBlock(cloud.camera_forward, cloud.camera_right, cloud.camera_up, cloud.image);
  bool valid;
  // A reduced-grid pixel p stands for the full image's pixels [d p, d p + d): its ray goes through their
  // centre, d p + d/2 in full-image pixels (exactly where the upsampling puts it), or, for temporal
  // reprojection, through the centre of this frame's pixel of the block, d p + o + 1/2.
  vec2 imagePoint = vec2(pixel) * float(push.divisor) + push.pointOffset;
  vec3 dir = cameraRayDirection(camera, imagePoint, valid);
  uint index = uint(pixel.y) * push.tiles.width + uint(pixel.x);
  vec4 skyValue = push.composite != 0 ? skyFrame.pixels[index] : vec4(0.0);
  if (!valid) {
    if (push.firstBatch != 0) {
      cloudFrame.pixels[index] = vec4(0.0, 0.0, 0.0, 1.0);
      cloudDepth.depth[index] = cloud.sun_direction.w;
    }
    return;
  }
  vec3 sun = cloud.sun_direction.xyz;
  vec3 origin = cloud.camera_position.xyz;
  float r = max(length(origin), atmosphere.bottom_radius + 0.01);
  origin = normalize(origin) * r;
  float mu = clamp(dot(origin, dir) / r, -1.0, 1.0);
  float nu = dot(dir, sun);

  // 1. The stretches inside the shells, before the ground and the march limit, sorted by start.
  float tMax = cloud.sun_direction.w;
  if (rayIntersectsGround(r, mu, atmosphere.bottom_radius)) tMax = min(tMax, distanceToBottomAtmosphereBoundary(r, mu, atmosphere.bottom_radius));
  if (kTerrainDepth) {
    ivec2 imagePixel = clamp(ivec2(imagePoint), ivec2(0), ivec2(cloud.image.xy) - 1);
    uint terrainIndex = uint(imagePixel.y * cloud.image.x + imagePixel.x);
    if (terrainIndex < uint(terrainDepth.t.length())) tMax = min(tMax, terrainDepth.t[terrainIndex]);
  }
  vec2 segments[kMaxSegments];
  int segmentLayer[kMaxSegments];
  int count = 0;
  float total = 0.0;
  for (int i = 0; i < cloud.image.w; ++i) {
    CloudLayer layer = layerAt(i);
    vec2 first, second;
    cloudShellSegments(r, mu, layer.bottom_radius, layer.top_radius, tMax, first, second);
    if (first.y > first.x) { segments[count] = first; segmentLayer[count] = i; total += first.y - first.x; ++count; }
    if (second.y > second.x) { segments[count] = second; segmentLayer[count] = i; total += second.y - second.x; ++count; }
  }
  for (int i = 1; i < count; ++i)  // insertion sort by start
    for (int j = i; j > 0 && segments[j].x < segments[j - 1].x; --j) {
      vec2 s = segments[j]; segments[j] = segments[j - 1]; segments[j - 1] = s;
      int l = segmentLayer[j]; segmentLayer[j] = segmentLayer[j - 1]; segmentLayer[j - 1] = l;
    }

  // 2.-3. The march.
  int viewSteps = max(cloud.steps.x, 1);
  int lightSteps = max(cloud.steps.y, 1);
  // The other layers' crossings: lightSteps x CloudMarchSettings::otherLayerLightStepsScale per thickness.
  int otherLayerSteps = max(int(float(lightSteps) * cloud.weatherPlanet.w + 0.5), 1);
  int octaves = clamp(cloud.steps.z, 1, 8);
  bool jitter = (cloud.steps.w & 2) != 0;
  bool ambientOn = (cloud.steps.w & 4) != 0;
  float lightLength = cloud.phaseLight.w;
  float albedo = cloud.phase.w;
  // The light paths' δ-scaled transport and phase mean cosine (cloud_sampling.glsl; the floor's weight is
  // per layer: `diffusion`).
  float transportScale = cloudLightTransportScale();
  float phaseMeanCosine = cloudLightPhaseMeanCosine();
  float bottomVisibility = cloud.march.x;
  float earlyExit = cloud.knobs.earlyExitTransmittance;
  float buildUpScale = cloud.buildUp.x;  // CloudMarchSettings::msBuildUpScale k (0: off)
  bool ambientSlab = cloud.buildUp.y > 0.5;  // CloudMarchSettings::ambientSlab
  // CloudMarchSettings::ambientThroughOtherLayers, where the column map's ambient slices are baked
  bool ambientThroughOthers = kSeveralLayers && cloud.buildUp.z > 0.5;
  float ambientFlow = cloud.buildUp.w;  // CloudMarchSettings::ambientFlow (0: the slab's J alone)
  int coarse = max(int(cloud.march.z + 0.5), 1);
  float emptyMargin = cloud.knobs.emptySpaceMargin;  // per thickness of the span
  float cone = kLightCone ? cloud.knobs.lightCone : 0.0;
  bool uniformSteps = (cloud.steps.w & 8) != 0;
  bool lightToExit = (cloud.steps.w & 16) != 0;
  bool msZenith = (cloud.steps.w & 32) != 0;
  bool msScattered = (cloud.steps.w & 64) != 0;
  bool lightScaled = (cloud.steps.w & 128) != 0;
  bool throughOthers = kOtherLayers && (cloud.steps.w & 256) != 0 && cloud.image.w > 1;
  bool exitRemainder = (cloud.steps.w & 512) != 0;
  bool reflectedLowSunDepth = (cloud.steps.w & 1024) != 0;  // CloudMarchSettings::reflectedLowSunDepth
  float lodScale = cloud.aerial.z;  // CloudMarchSettings::noiseLodScale (0: level 0 everywhere)
  float uniformStep = max(total / float(viewSteps), 1e-3);
  float baseStep = max(cloud.stepGrowth.x, 1e-3);
  float growthStart = max(cloud.stepGrowth.y, 1.0);
  float maxFactor = cloud.stepGrowth.z;
  float lowTransmittanceStart = cloud.weatherPlanet.y;  // CloudMarchSettings::lowTransmittanceStepStart T1 (0: off)
  float lowTransmittanceMax = cloud.weatherPlanet.z;    // CloudMarchSettings::lowTransmittanceStepMax K
  uint viewCount = 0u, lightCount = 0u;
  ivec2 blueSize = textureSize(blueNoise, 0);
  float xi = jitter ? fract(texelFetch(blueNoise, (pixel + push.noiseShift) % blueSize, 0).r + push.jitterShift) : 0.5;
  // Per octave of the current layer (set when the march enters a layer): the phase for this pixel's
  // scattering angle, the extinction scale a^i, the weight b^i, and the most the way down from the layer
  // top can pass (cloudOctaveTransmittanceBound, with a 1e-4 margin for its float rounding).
  float phaseOctave[8], octaveScale[8], octaveWeight[8], octaveTopBound[8], octaveShare[8];
  int phaseLayer = -1;  // the layer the octave arrays hold
  float diffusion = 0.0;  // that layer's diffusion-floor weight d
  float baseLimb = 0.0;   // and its base's limb darkening (cloudBaseLimbFactor's strength)
  float reflectWeight = 0.0, reflectDepthScale = 0.0;  // that layer's reflected light's r and a_r
  float lowSunMu = 0.0;                                // that layer's low-sun scale's mu_0 (0: off)
  vec2 texels = vec2(1.0);  // that layer's noise texel sizes (noiseTexels)

  float transmittance = 1.0;       // the true one: the alpha, opacity and depth
  float lightTransmittance = 1.0;  // the δ-scaled one the in-scattered light sees (= transmittance without a peak)
  vec3 sunlike = vec3(0.0);  // cloud light with the sun's spectrum, at the batch's wavelengths
  vec3 skylike = vec3(0.0);  // cloud light with the sky's spectrum
  // The last cloud sample's sources S (the early exit's remainder, below).
  vec3 lastSunSource = vec3(0.0), lastSkySource = vec3(0.0);
  float depthSum = 0.0, depthWeight = 0.0;
  // The light of orders >= 2 the build-up along the view takes off (cloudBuildUpDecay): R = sum_i c_i
  // e^(-k (tau_now - tau_i)), kept in the sun's units as sunlike.
  vec3 buildUpLost = vec3(0.0);
  // Hard cap on samples (segment ends add partial steps). Growing steps: a stretch [t0, t1] takes
  // N (1 + ln(G)) + N (t1 - G D) / (G D) steps at most (common/cloud_march.glsl); with t1 <= 80 km and
  // D >= 1 km that stays below ~8 N for G >= 10, hence 8 N.
  int budget = (uniformSteps ? 4 : 8) * viewSteps + 64;
  // The march alternates two phases: (a) step along the ray (coarse empty-space steps, fine steps of
  // density 0, from segment to segment) until a sample with cloud, then (b) light that sample. Lanes of
  // a SIMD group (lavapipe's 8-wide vectors, a GPU's warp) that found their sample wait in (a) for the
  // others, so (b), the expensive part, runs with most lanes busy; written as one loop with the lighting
  // under "this lane has cloud", (b) ran whenever any lane had cloud (the while-while traversal of
  // Aila and Laine 2009, "Understanding the efficiency of ray traversal on GPUs").
  int s = -1;                  // the segment being marched (-1: none yet)
  float t = 0.0, end = 0.0;    // the march's distance along the ray, and where the segment ends
  int emptyRun = coarse;       // fine steps without cloud since the last cloud (>= coarse: coarse mode)
  CloudLayer layer = layerAt(0);
  if (!kSeveralLayers) texels = noiseTexels(layer);
  while (true) {
    // (a) The next sample with cloud: its step h, point p, density d and noise LOD.
    bool found = false;
    float h = 0.0, d = 0.0;
    vec3 p = origin;
    vec2 lod = vec2(0.0);
    // lavapipe (gallivm) runs every branch of a loop body under a mask, whichever way its lanes go
    // (docs/gpu.md), so an iteration costs all the code in it: each iteration evaluates the shape at
    // one point, for the coarse test or for the fine sample, and the per-layer set-up waits for (b).
    while (lightTransmittance > earlyExit && budget > 0) {
      if (!(t < end)) {  // the next segment
        if (++s >= count) break;
        if (kSeveralLayers) {
          layer = layerAt(segmentLayer[s]);
          texels = noiseTexels(layer);
        }
        t = segments[s].x;
        end = segments[s].y;
        emptyRun = coarse;  // start in coarse mode
        continue;
      }
      float dt = (uniformSteps ? uniformStep : cloudViewStep(t, baseStep, growthStart, maxFactor)) *
                 cloudLowTransmittanceStepFactor(lightTransmittance, lowTransmittanceStart, lowTransmittanceMax);
      // The noise LOD: the view step's length is the lookups' footprint (the march samples no finer),
      // times the scale; the coarse test, the sample and its light marches read the same levels.
      lod = noiseLod(texels, lodScale * dt);
      // Coarse step: the shape-only density at one point of the next `coarse` fine steps. The span is
      // skipped only if that point lies outside the shape by more than a margin proportional to the
      // span (a Lipschitz-like bound: the unsampled rest of the span cannot reach the shape). Without
      // the margin a span whose point just missed a thin fringe lost it, which dimmed a sunset's
      // forward-scattering edges by 16 % (docs/clouds.md, "Empty-space skipping"). A map with sharp
      // coverage: a span is skipped only where no coverage lies within its reach (the span no longer
      // than the block's bound, so that all its points lie within the reach).
      bool coarseStep = emptyRun >= coarse && coarse > 1;
      bool byReach = kWeatherReach && coarseStep && cloud.weatherReach.x > 0.0;
      float span = !coarseStep ? min(dt, end - t) : byReach ? min(min(float(coarse) * dt, end - t), cloud.weatherReach.y)
                                                             : min(float(coarse) * dt, end - t);
      vec3 q = origin + dir * (t + xi * span);
      ++viewCount;
      CloudLayer column;
      float ph;
      vec3 local;
      float shape = -1.0;
      if (!byReach) shape = shapeSignedDensityAt(layer, q, lod, column, ph, local);
      if (coarseStep) {
        bool skip = byReach ? textureLod(weatherReachMap, weatherCoordinateAt(layer, q), 0.0).r <= 0.0
                            : shape <= -emptyMargin * span / growthStart;
        if (skip) {
          --budget;
          t += span;
          continue;
        }
        emptyRun = 0;  // cloud ahead: march this stretch in fine steps (the next iteration)
        continue;
      }
      --budget;  // a coarse test that found cloud and its first fine step count as one, as they always have
      h = span;
      p = q;
      d = densityFromShape(column, ph, local, max(shape, 0.0), lod);
      if (d <= 0.0) {
        ++emptyRun;
        t += h;
        continue;
      }
      emptyRun = 0;
      found = true;
      break;
    }
    if (!found) break;
    if ((kSeveralLayers ? segmentLayer[s] : 0) != phaseLayer) {
      // The layer's octave parameters a, b, c (cloud_sampling.glsl: the w components of its vec4s).
      phaseLayer = kSeveralLayers ? segmentLayer[s] : 0;
      float a = cloud.layers[phaseLayer].msA;
      float b = cloud.layers[phaseLayer].msB;
      float c = cloud.layers[phaseLayer].msC;
      diffusion = cloud.layerLighting[phaseLayer].floorWeight;
      baseLimb = cloud.layerLighting[phaseLayer].baseLimb;
      reflectWeight = cloud.layerLighting[phaseLayer].reflectWeight;
      reflectDepthScale = cloud.layerLighting[phaseLayer].reflectDepthScale;
      lowSunMu = cloud.layerLowSun[phaseLayer / 4][phaseLayer % 4];
      float weightScale = cloudOctaveWeightScale(b, octaves);
      for (int o = 0; o < octaves; ++o) {
        phaseOctave[o] = cloudPhase(cloud.phase.x * cloudOctaveEccentricityScale(c, o), cloud.phase.y * cloudOctaveEccentricityScale(c, o),
                                    cloud.phase.z, cloud.phaseLight.x, nu);
        octaveScale[o] = cloudOctaveExtinctionScale(a, o);
        octaveWeight[o] = cloudOctaveWeight(b, o) * (o > 0 ? weightScale : 1.0);
        octaveTopBound[o] = 1.0001 * cloudOctaveTransmittanceBound(octaveScale[o], msScattered);
      }
      // Octave i's share b^i / sum_j b^j (j >= 1) of a deck's slab transmission (cloudOctaveTransmittanceThroughOthers).
      float weights = 0.0;
      for (int o = 1; o < octaves; ++o) weights += octaveWeight[o];
      for (int o = 1; o < octaves; ++o) octaveShare[o] = weights > 0.0 ? octaveWeight[o] / weights : 0.0;
    }

    // (b) The sample's light.
    {
      float sigmaT = layer.extinction * d;
      float sigmaS = albedo * sigmaT;
      float rp = length(p);
      float muS = dot(p, sun) / rp;
      float ph = cloudHeightFraction(layer, rp);
      // Sun: atmosphere transmittance at the sample, cloud optical depth by the light march.
      vec3 sunLight = transmittanceToSun(transmittanceLut, atmosphere, rp, muS) * atmosphere.solar_irradiance;
      bool sunVisible = max(sunLight.x + sunLight.y + sunLight.z, 0.0) > 0.0;
      float tau = 0.0;
      float tauOther = 0.0;  // the other layers' part of tau (0 with the shadow map: tau has it)
      float tauBehind = 0.0;  // the own layer's optical depth behind p along the sun (cloudReflectedSource)
      bool behindFromMap = false;
      // The reflected light is a source of octaves i >= 1: with one octave its way behind is not needed.
      bool reflects = kReflection && reflectWeight > 0.0 && octaves > 1;
      if (sunVisible) {
        // The Beer shadow map where enabled and p lies on it (all layers); else the light march.
        vec3 shadow = vec3(0.0);
        bool onShadowMap = false;
        if (kShadowMap) {
          shadow = cloudShadowCoordinate(p, cloud.shadowCentre.xyz, cloud.shadowAxisU.xyz, cloud.shadowAxisV.xyz, sun,
                                         cloud.shadowCentre.w, cloud.shadowAxisU.w);
          onShadowMap = cloud.shadowSize.z != 0 && cloudShadowCovers(shadow);
        }
        if (onShadowMap) {
          tau = cloudShadowOpticalDepth(textureLod(shadowMap, shadow.xy, 0.0), shadow.z);
          lightCount += 1u;
        } else {
          // Bit 16: march to where the sun ray leaves the layer (at most lightLength); else the first
          // milestone's fixed length (the thickest layer's thickness, at most 4 km), for comparisons.
          float marchLength = lightToExit ? cloudSunExitDistance(layer, p, sun, lightLength) : lightLength;
          // Bit 128: as many steps per layer thickness of the way as a vertical way gets, up to 4x
          // (a grazing sun crosses a 1 km layer over ~11 km: 6 steps there left ~2 km between samples).
          int n = lightScaled && lightToExit ? lightStepsForLength(lightSteps, marchLength, layer.top_radius - layer.bottom_radius, lightSteps)
                                             : lightSteps;
          // The deep shadow map where baked and p's sun ray climbs from p on (p.sun > 0): the first
          // `near` of the n steps marched, the rest of the way to the top, from where they end, read
          // from the map.
          bool fromMap = kDeepShadowMap && cloud.deepShadowMap.w > 0.0 && lightToExit && muS > 0.0;
          int taken = n;
          if (fromMap) {
            // At least one of the map's level segments (H / (K mu_s) along the sun) is marched: a lit
            // sample lies in cloud, so the density next to it is higher than its segment's mean, which
            // the map's linear interpolation between levels assumes (with a low sun a segment is
            // ~0.7 km long: reading it from the sample on made the single scattering +20 % too bright).
            float segment = (layer.top_radius - layer.bottom_radius) / (cloud.deepShadowMap.y * max(muS, 1e-3));
            int nearSegment = int(ceil(float(n) * sqrt(min(segment / max(marchLength, 1e-3), 1.0))));
            taken = min(max(int(cloud.deepShadowMap.z + 0.5), nearSegment), n);
          }
          tau = opticalDepthToSunTaken(layer, p, sun, n, taken, marchLength, cone, lod);
          lightCount += uint(taken);
          // The map's texel of the line that p and q share (q lies on p's sun ray), projected once for
          // both lookups below.
          int mapLayer = kSeveralLayers ? segmentLayer[s] : 0;
          vec2 mapTexel = vec2(0.0);
          if (fromMap && taken < n) {
            float f = float(taken) / float(n);
            vec3 q = p + sun * (marchLength * f * f);
            vec2 planePoint = deepShadowMapPlanePoint(q);
            mapTexel = deepShadowMapTexel(planePoint);
            tau += deepShadowMapOpticalDepth(deepShadowMap, mapLayer, layer, q, planePoint, mapTexel);
          } else if (reflects && fromMap) {
            mapTexel = deepShadowMapTexel(deepShadowMapPlanePoint(p));
          }
          // The reflected light's medium behind p (cloudReflectedSource): from the deep shadow map, p's
          // line's whole crossing less p's way to the top.
          if (reflects && fromMap) {
            tauBehind = max(deepShadowMapCrossing(deepShadowMap, mapLayer, mapTexel) - tau, 0.0);
            behindFromMap = true;
          }
          // Bit 256: the other layers the sun ray crosses shadow p too (the path tracer's medium has them all).
          if (throughOthers) {
            if (kOtherLayerMap && cloud.otherLayerMap.w > 0.0)  // baked this frame (its samples counted as the maps')
              tauOther = otherLayerMapOpticalDepth(otherLayerMap, segmentLayer[s], p, rp);
            else if (kOtherLayerMarch)
              tauOther = opticalDepthThroughOtherLayers(segmentLayer[s], p, rp, muS, sun, otherLayerSteps, lightLength, lod, lightCount);
          }
        }
        // Else the way behind p (away from the sun, to where it leaves the layer) is marched in
        // lightSteps / 2 samples (at least 2), as the way up to the top is without the column map.
        if (kReflectionMarch && reflects && !behindFromMap) {
          int behindSteps = max(lightSteps / 2, 2);
          tauBehind = opticalDepthToSun(layer, p, -sun, behindSteps, cloudSunExitDistance(layer, p, -sun, lightLength), 0.0, lod);
          lightCount += uint(behindSteps);
        }
        tauOther *= transportScale;
        tauBehind *= transportScale;
        tau = transportScale * tau + tauOther;
      }
      // Octaves i >= 1 (light scattered before it reaches the sample; docs/clouds.md "Multiple
      // scattering"): with flag 32 it takes the better of two ways in, along the sun ray (irradiance E,
      // optical depth tau_sun) or diffusing down from the layer top (E mu_s on a horizontal top, times
      // the Eddington angular factor, cloudTopEntryWeight; optical depth tau_up straight up): at a low
      // sun the sun ray crosses ~10 km of cloud while scattered light arrives from above. Flag 64: only the scattered part (cloudOctaveTransmittance).
      float tauUp = -1.0;
      float topWeight = cloudTopEntryWeight(muS);
      // The way from the top can only win the max below if, for some octave, its best case (any
      // tau_up, octaveTopBound) beats the sun ray's value: otherwise its march is skipped with the same
      // result.
      float sunAttenuation[8];
      bool upCanWin = false;
      // The light through the other layers (tauOther > 0) takes cloudOctaveTransmittanceThroughOthers,
      // each octave its share of the deck's diffuse light (once per sample); the top path's bound is then 1.
      float tauOwn = tau - tauOther;
      bool throughDeck = kOtherLayers && tauOther > 0.0;
      float deckLight = throughDeck ? cloudDeckDiffuseLight(tauOther, muS, phaseMeanCosine) : 0.0;
      for (int o = 1; o < octaves; ++o) {
        sunAttenuation[o] = throughDeck ? cloudOctaveTransmittanceThroughOthers(octaveScale[o], tauOwn, tauOther, deckLight, octaveShare[o], msScattered)
                                        : cloudOctaveTransmittance(octaveScale[o], tau, msScattered);
        if (topWeight * (throughDeck ? 1.0 : octaveTopBound[o]) > sunAttenuation[o]) upCanWin = true;
      }
      // One march straight up serves the way from the top (lightSteps / 2 samples, at least 2, where it
      // can win) and the diffusion floor below (2 samples, where only the floor needs it): lavapipe runs
      // a loop's body at least once even where no lane needs it, so two such loops cost more than one.
      vec3 up = p / rp;
      bool wantTop = msZenith && octaves > 1 && sunVisible && muS > 0.0 && upCanWin;
      bool wantFloor = diffusion > 0.0 && octaves > 1 && sunVisible && muS > 0.0;
      bool wantAmbientColumn = ambientOn && ambientSlab;
      const int floorSteps = 2;
      // From the column map when baked (both ways in two lookups; its samples counted as the maps').
      bool columnsFromMap = kColumnMap && cloud.columnMap.w > 0.0;
      float tauDown = 0.0;
      if (columnsFromMap && (wantTop || wantFloor || wantAmbientColumn)) {
        vec2 depths = transportScale * columnMapOpticalDepths(columnMap, kSeveralLayers ? segmentLayer[s] : 0, layer, p, rp);
        tauUp = depths.x;
        tauDown = depths.y;
      }
      int upSteps = !kColumnMarch || columnsFromMap ? 0 : wantTop ? max(lightSteps / 2, 2) : wantFloor || wantAmbientColumn ? floorSteps : 0;
      if (upSteps > 0) {
        tauUp = transportScale * opticalDepthToSun(layer, p, up, upSteps, cloudSunExitDistance(layer, p, up, lightLength), 0.0, lod);
        lightCount += uint(upSteps);
      }
      float msSum = 0.0;
      for (int o = 1; o < octaves; ++o) {
        float attenuation = sunAttenuation[o];
        // The way from the top starts where the sun ray reaches this layer, past the others: tau_up + their tau.
        if (wantTop)
          attenuation = max(attenuation, topWeight * (throughDeck ? cloudOctaveTransmittanceThroughOthers(octaveScale[o], tauUp, tauOther, deckLight,
                                                                                                          octaveShare[o], msScattered)
                                                                  : cloudOctaveTransmittance(octaveScale[o], tauUp + tauOther, msScattered)));
        msSum += octaveWeight[o] * phaseOctave[o] * attenuation;
      }
      // The layer's low-sun scale (cloudOctaveLowSunScale; 1 when off or the sun is high).
      float lowSunScale = cloudOctaveLowSunScale(muS, lowSunMu);
      msSum *= lowSunScale;
      // The diffusion floor (cloudEddingtonSlabSource): the layer as a slab between its top and base
      // through p, straight up and down, its weight the layer's ms_d; the better of it and the octaves.
      // Two samples down (and tau_up above) for the floor and the ambient: both are smooth functions of
      // the depths (linear in them when thick).
      if ((wantFloor || wantAmbientColumn) && kColumnMarch && !columnsFromMap) {
        tauDown = transportScale * opticalDepthToSun(layer, p, -up, floorSteps, cloudSunExitDistance(layer, p, -up, lightLength), 0.0, lod);
        lightCount += uint(floorSteps);
      }
      if (wantFloor) {
        // The other layers above take from the slab's incident flux what they turn back: for diffuse flux a
        // medium of optical depth tau acts like (1 - g) tau (similarity relation, van de Hulst 1980), so a thin
        // forward-scattering deck above passes most of the flux, scattered, though little of the direct beam.
        float fluxThroughOthers = exp(-(1.0 - phaseMeanCosine) * tauOther);
        msSum = max(msSum, diffusion * fluxThroughOthers * cloudFloorSunFactor(muS) *
                               cloudEddingtonSlabSource(muS, tauUp, tauUp + tauDown, phaseMeanCosine, dot(dir, up)) *
                               cloudBaseLimbFactor(dot(dir, up), tauDown, transmittance, baseLimb));
      }
      float msFromSunSide = msSum;  // the octaves and the floor: what builds up along the view (below)
      // The light the cloud behind p turns back towards the sun (cloudReflectedSource), added to the octaves;
      // under a low sun its depth scale grows with the scale's inverse (cloudReflectedLowSunDepthScale).
      if (reflects && sunVisible) {
        float depthScale = reflectedLowSunDepth ? cloudReflectedLowSunDepthScale(reflectDepthScale, lowSunScale) : reflectDepthScale;
        msSum += lowSunScale * reflectWeight * cloudReflectedSource(tauBehind, tau, phaseMeanCosine, depthScale, nu);
      }
      float octaveSum = phaseOctave[0] * exp(-tau) + msSum;
      vec3 sunSource = sunLight * octaveSum;
      vec3 skySource = vec3(0.0);
      if (ambientOn) {
        // Ambient: (L_sky v_sky + L_ground v_ground) / 2 (common/cloud_lighting.glsl).
        vec3 skyIrradiance = irradianceLookup(skyIrradianceLut, atmosphere, rp, muS);
        float rg = atmosphere.bottom_radius;
        vec3 groundSun = transmittanceToSun(transmittanceLut, atmosphere, rg, muS) * atmosphere.solar_irradiance * max(muS, 0.0);
        vec3 groundSky = irradianceLookup(skyIrradianceLut, atmosphere, rg, muS);
        // J = (1 - w) L_sky + w L_ground written as (v_sky L_sky + v_ground L_ground) / 2.
        // With the other layers (from the column map only): their whole columns above and below.
        vec2 othersUpDown = vec2(0.0);  // similarity-scaled already
        if (wantAmbientColumn && ambientThroughOthers)
          othersUpDown = columnMapOtherLayersOpticalDepths(columnMap, segmentLayer[s], p, rp);
        float groundWeight = wantAmbientColumn ? cloudAmbientViewGroundWeight((1.0 - phaseMeanCosine) * max(tauUp, 0.0) + othersUpDown.x,
                                                                              (1.0 - phaseMeanCosine) * tauDown + othersUpDown.y,
                                                                              ambientFlow * phaseMeanCosine, dot(dir, up)) : 0.5;
        float vSky = wantAmbientColumn ? 2.0 * (1.0 - groundWeight) : cloudSkyVisibility(ph, bottomVisibility);
        float vGround = wantAmbientColumn ? 2.0 * groundWeight : cloudGroundVisibility(ph, bottomVisibility);
        vec3 reflectance = atmosphere.ground_albedo / kPi;
        skySource = 0.5 * (vSky * skyIrradiance / kPi + vGround * reflectance * groundSky);
        sunSource += 0.5 * vGround * reflectance * groundSun;
      }
      // sigma_s = omega sigma_t with the scene's phase at the first octave (TMS: the scaled medium's
      // omega' sigma_t' p' with the truncated phase p' replaced by p / (1 - f)).
      float sigmaTLight = transportScale * sigmaT;
      float dTauLight = sigmaTLight * h;  // the step's δ-scaled optical depth
      // A source S adds T sigma_s S (1 - e^(-sigma_t h)) / sigma_t over the step (cloudStepIntegral).
      float stepWeight = lightTransmittance * sigmaS * cloudStepIntegral(sigmaTLight, h);
      sunlike += stepWeight * sunSource;
      skylike += stepWeight * skySource;
      // The same step's light of orders >= 2 from the sun's side, into the build-up's running sum.
      if (buildUpScale > 0.0)
        buildUpLost = buildUpLost * cloudBuildUpDecay(buildUpScale, dTauLight) +
                      stepWeight * sunLight * msFromSunSide * cloudBuildUpStepWeight(buildUpScale, dTauLight);
      lastSunSource = sunSource;
      lastSkySource = skySource;
      lightTransmittance *= exp(-dTauLight);
      float stepT = exp(-sigmaT * h);
      float opacity = transmittance * (1.0 - stepT);
      depthSum += opacity * (t + 0.5 * h);
      depthWeight += opacity;
      transmittance *= stepT;
      t += h;
    }
  }

  // The build-up along the view (cloudBuildUpDecay): the ray left the cloud, so each step's light of
  // orders >= 2 loses e^(-k tau_behind). After an early exit the rest of the ray is opaque (tau_behind
  // infinite): nothing is lost.
  bool exitedEarly = lightTransmittance <= earlyExit;
  if (!exitedEarly) sunlike = max(sunlike - buildUpLost, vec3(0.0));

  // The early exit (docs/clouds.md "Early exit"): the march stopped inside cloud with the light's
  // transmittance at or below earlyExit. The rest of the ray is taken as the last sample's cloud going
  // on, whose light is T sigma_s S / sigma_t (its step integral's limit: what that sample would give at
  // any thickness), and as opaque (alpha 0), so that the sky behind is not added as well. sigma_s /
  // sigma_t = albedo sigma_t / (transportScale sigma_t), the same for every sample.
  if (exitRemainder && exitedEarly) {
    float perExtinction = albedo / max(transportScale, 1e-6);
    sunlike += lightTransmittance * perExtinction * lastSunSource;
    skylike += lightTransmittance * perExtinction * lastSkySource;
    transmittance = 0.0;
  }

  // 4. Aerial perspective to the cloud's mean depth (none without cloud: opacity 0 below).
  vec3 airLight = vec3(0.0), airT = vec3(1.0);
  float meanDepth = depthWeight > 0.0 ? depthSum / depthWeight : 0.0;
#if CLOUD_AERIAL_PERSPECTIVE == 2
  aerialPerspectiveLookup(aerialVolume, imagePoint, cloud.image.xy, meanDepth, cloud.aerial.x,
                          cornetteShanksPhase(atmosphere.mie_phase_g, nu), airLight, airT);
#elif CLOUD_AERIAL_PERSPECTIVE == 1
  if (depthWeight > 0.0) airToDepth(atmosphere, origin, dir, sun, meanDepth, max(int(cloud.aerial.y + 0.5), 1), airLight, airT);
#endif
  float opacity = 1.0 - transmittance;
  vec3 light = skyRadianceToRgb() * (airT * skylike) + sunRadianceToRgb() * (airT * sunlike) + opacity * airLight;

  // 5. Composite.
  //    A still's sub-frames sum (L, T) weighted by 1/N first (one sub-frame: weight 1, the same values).
  vec4 fresh = push.sampleWeight * vec4(light, transmittance);
  if (push.firstBatch != 0) {
    atomicAdd(counters.viewSamples, viewCount);
    atomicAdd(counters.lightSamples, lightCount);
    vec4 sum = push.subFrame == 0 ? fresh : cloudFrame.pixels[index] + fresh;
    cloudFrame.pixels[index] = sum;
    cloudDepth.depth[index] = depthWeight > 0.0 ? meanDepth : count > 0 ? segments[0].x : tMax;
    if (push.composite != 0 && push.lastSubFrame != 0) skyFrame.pixels[index] = vec4(skyValue.rgb * sum.a + sum.rgb, skyValue.a);
  } else {
    vec4 previous = cloudFrame.pixels[index];
    cloudFrame.pixels[index] = vec4(previous.rgb + fresh.rgb, previous.a);
    if (push.composite != 0) skyFrame.pixels[index] = vec4(skyValue.rgb + fresh.rgb, skyValue.a);
  }
}
