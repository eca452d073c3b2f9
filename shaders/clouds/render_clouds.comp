#version 450
#extension GL_GOOGLE_include_directive : require
// Cloud layers over the clear sky (docs/clouds.md). Per pixel:
//  1. the view ray's stretches inside every layer's shell (common/cloud_density.glsl), in order;
//  2. a march of fine steps growing with the distance from the camera (common/cloud_march.glsl: the
//     base step is the thickest layer's thickness / `view steps`, growing in proportion to distance
//     beyond one thickness, capped), or, with the uniform flag, `view steps` equal steps spread over the
//     stretches' total length; blue-noise jitter; coarse steps of the shape-only density until it is
//     non-zero (empty-space skipping; exact, since the shape-only density bounds the full one); an
//     early exit at low transmittance;
//  3. at every step with cloud: sunlight through the atmosphere (transmittance table at the sample)
//     and through the cloud (a light march of `light steps` in a cone), dual-lobe Henyey-Greenstein,
//     octave multiple scattering; ambient from the sky irradiance table and the ground; each step
//     integrated with Hillaire 2016's energy-conserving formula (cloudStepIntegral);
//  4. aerial perspective to the transmittance-weighted mean depth of the cloud: the air's
//     transmittance and in-scattering up to there (a short march of the clear-sky integrand);
//  5. composite over the sky image: out = T_cloud * sky + L, with L = T_air L_cloud + (1 - T_cloud) L_air.
// Radiance is carried at the batch's three wavelengths in two parts, light with the sun's spectrum and
// light with the sky's, converted to Rec.709 cd/m^2 with the atmosphere block's matrices.
#include "atmosphere/atmosphere_sampling.glsl"
#include "atmosphere/irradiance_sampling.glsl"
#include "common/camera.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_lighting.glsl"
#include "common/cloud_march.glsl"
#include "common/cloud_weather.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3) uniform sampler2D skyIrradianceLut;
layout(set = 0, binding = 4) uniform sampler3D shapeNoise;   // linear, repeat
layout(set = 0, binding = 5) uniform sampler3D detailNoise;  // linear, repeat
layout(set = 0, binding = 6) uniform sampler2D curlNoise;    // linear, repeat
layout(set = 0, binding = 7) uniform sampler2D blueNoise;    // read with texelFetch
layout(set = 0, binding = 8, rgba32f) uniform image2D skyImage;    // read, composited, written
layout(set = 0, binding = 9, rgba32f) uniform image2D cloudImage;  // rgb: cloud light L; a: T_cloud
layout(std140, set = 0, binding = 10) uniform CloudBlock {
  vec4 camera_position;  // planet-centred, m
  vec4 camera_forward;   // xyz; w = horizontal fov (rad)
  vec4 camera_right;     // xyz; w = yaw (rad)
  vec4 camera_up;        // xyz
  vec4 sun_direction;    // xyz; w = largest march distance (m)
  ivec4 image;           // width, height, projection, layer count
  ivec4 steps;           // view steps, light steps, octaves, flags (1 aerial perspective, 2 jitter, 4 ambient, 8 uniform steps)
  vec4 octaves;          // a, b, c, light march length (m)
  vec4 phase;            // g forward, g back, back weight, single-scattering albedo
  vec4 march;            // ambient bottom visibility, early-exit transmittance, coarse factor, light cone tan
  vec4 stepGrowth;       // base step h0 (m), growth start D (m), largest step factor G, unused
  vec4 weatherRegion;    // weather map: width (m), height (m), skew east, skew north (m per m)
  vec4 weatherPlanet;    // planet (ground) radius (m), unused x3
  vec4 layers[8 * 5];    // 5 vec4 per layer, see layerAt
} cloud;
// Sample counters (summed over the pixels by the first batch): view-march density evaluations (coarse
// and fine), light-march density evaluations.
layout(set = 0, binding = 12) uniform sampler2D weatherMap;  // linear, repeat (common/cloud_weather.glsl)
layout(std430, set = 0, binding = 11) buffer CloudCounters { uint viewSamples; uint lightSamples; } counters;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  int firstBatch;  // 1: write (composite over the sky); 0: add this spectral batch's light
  int pad0;
  int pad1;
  int pad2;
} push;

const int kMaxSegments = 16;  // two stretches per layer, 8 layers

CloudLayer layerAt(int i) {
  vec4 a = cloud.layers[5 * i];
  vec4 b = cloud.layers[5 * i + 1];
  vec4 c = cloud.layers[5 * i + 2];
  vec4 d = cloud.layers[5 * i + 3];
  vec4 e = cloud.layers[5 * i + 4];
  CloudLayer layer;
  layer.bottom_radius = a.x;
  layer.top_radius = a.y;
  layer.coverage = a.z;
  layer.extinction = a.w;
  layer.density_scale = b.x;
  layer.anvil = b.y;
  layer.shape_period = b.z;
  layer.detail_period = b.w;
  layer.detail_strength = c.x;
  layer.curl_period = c.y;
  layer.curl_strength = c.z;
  layer.wind_offset = d.xyz;
  layer.skew = e.xy;
  layer.kind = int(e.z + 0.5);
  return layer;
}

// The shape-only density SN_nd at p (0 outside the shell or where the weather map has no cloud); the
// weather map's column layer, ph and local are returned for the detail.
float shapeDensityAt(CloudLayer layer, vec3 p, out CloudLayer column, out float ph, out vec3 local) {
  float r = length(p);
  column = layer;
  local = vec3(0.0);
  ph = cloudHeightFraction(layer, r);
  if (ph <= 0.0 || ph >= 1.0) return 0.0;
  float planet = cloud.weatherPlanet.x;
  vec4 weather = textureLod(weatherMap, cloudWeatherCoordinate(p, planet, cloud.weatherRegion.xy, cloud.weatherRegion.zw), 0.0);
  bool empty;
  column = cloudColumnLayer(layer, weather, planet, empty);
  if (empty) return 0.0;
  ph = cloudHeightFraction(column, r);
  if (ph <= 0.0 || ph >= 1.0) return 0.0;
  local = cloudLocalPosition(column, p);
  vec4 shape = textureLod(shapeNoise, cloudShapeCoordinate(column, local), 0.0);
  return cloudShapeDensity(column, ph, shape, weather.x);
}

// The full density d at p.
float densityAt(CloudLayer layer, vec3 p) {
  CloudLayer column;
  float ph;
  vec3 local;
  float base = shapeDensityAt(layer, p, column, ph, local);
  if (base <= 0.0) return 0.0;
  vec2 curl = textureLod(curlNoise, cloudCurlCoordinate(column, local), 0.0).xy;
  vec4 detail = textureLod(detailNoise, cloudDetailCoordinate(column, local, curl, ph), 0.0);
  return cloudDensity(column, ph, base, detail);
}

// Optical depth towards the sun from p through `layer`: `n` samples at the midpoints of steps growing
// quadratically (boundaries L (j/n)^2), each pushed sideways within a cone of half-angle atan(cone)
// by a fixed kernel (Schneider 2015's cone sampling, deterministic here).
float opticalDepthToSun(CloudLayer layer, vec3 p, vec3 sun, int n, float length_m, float cone) {
  const vec2 kernel[6] = vec2[6](vec2(0.38, 0.92), vec2(-0.84, 0.28), vec2(0.59, -0.70), vec2(-0.15, -0.48),
                                 vec2(0.95, 0.05), vec2(-0.45, 0.62));
  vec3 t1 = normalize(abs(sun.z) < 0.9 ? cross(sun, vec3(0.0, 0.0, 1.0)) : cross(sun, vec3(1.0, 0.0, 0.0)));
  vec3 t2 = cross(sun, t1);
  float tau = 0.0;
  float previous = 0.0;
  for (int j = 1; j <= n; ++j) {
    float f = float(j) / float(n);
    float next = length_m * f * f;
    float mid = 0.5 * (previous + next);
    vec2 k = kernel[(j - 1) % 6] * cone * mid;
    tau += layer.extinction * densityAt(layer, p + sun * mid + t1 * k.x + t2 * k.y) * (next - previous);
    previous = next;
  }
  return tau;
}

// Air between the camera and distance d along dir: in-scattered light (sky-like and sun-like parts)
// and transmittance, by a short march of the clear-sky integrand of sky/sky_march.glsl (single
// Rayleigh + Mie scattering of sunlight through the transmittance table, Psi_ms for higher orders).
void airToDepth(AtmosphereParameters atmosphere, vec3 origin, vec3 dir, vec3 sun, float d, out vec3 sky,
                out vec3 sunlike, out vec3 transmittance) {
  const int kSteps = 8;
  sky = vec3(0.0);
  sunlike = vec3(0.0);
  transmittance = vec3(1.0);
  float nu = dot(dir, sun);
  float phaseR = rayleighPhase(nu);
  float phaseM = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
  float dt = d / float(kSteps);
  for (int i = 0; i < kSteps; ++i) {
    vec3 p = origin + dir * ((float(i) + 0.5) * dt);
    float r = length(p);
    float mu_s = dot(p, sun) / r;
    vec3 rayleigh = rayleighScatteringAt(atmosphere, r);
    vec3 mie = mieScatteringAt(atmosphere, r);
    vec3 extinction = extinctionAt(atmosphere, r);
    vec3 sunLight = transmittanceToSun(transmittanceLut, atmosphere, r, mu_s) * atmosphere.solar_irradiance;
    vec3 stepT = exp(-extinction * dt);
    vec3 integral = mix(dt * (1.0 - stepT) / max(extinction * dt, vec3(1e-12)), vec3(dt), lessThan(extinction * dt, vec3(1e-4)));
    sky += transmittance * (rayleigh * phaseR * sunLight + (rayleigh + mie) * multipleScattering(multipleScatteringLut, atmosphere, r, mu_s)) * integral;
    sunlike += transmittance * mie * phaseM * sunLight * integral;
    transmittance *= stepT;
  }
}

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  ivec2 pixel = ivec2(tiled);
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera;
  camera.forward = cloud.camera_forward.xyz;
  camera.right = cloud.camera_right.xyz;
  camera.up = cloud.camera_up.xyz;
  camera.fov = cloud.camera_forward.w;
  camera.yaw = cloud.camera_right.w;
  camera.projection = cloud.image.z;
  camera.width = cloud.image.x;
  camera.height = cloud.image.y;
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(pixel) + 0.5, valid);
  vec4 skyValue = imageLoad(skyImage, pixel);
  if (!valid) {
    if (push.firstBatch != 0) imageStore(cloudImage, pixel, vec4(0.0, 0.0, 0.0, 1.0));
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
  int octaves = clamp(cloud.steps.z, 1, 8);
  bool aerial = (cloud.steps.w & 1) != 0;
  bool jitter = (cloud.steps.w & 2) != 0;
  bool ambientOn = (cloud.steps.w & 4) != 0;
  float a = cloud.octaves.x, b = cloud.octaves.y, c = cloud.octaves.z;
  float lightLength = cloud.octaves.w;
  float albedo = cloud.phase.w;
  float bottomVisibility = cloud.march.x;
  float earlyExit = cloud.march.y;
  int coarse = max(int(cloud.march.z + 0.5), 1);
  float cone = cloud.march.w;
  bool uniformSteps = (cloud.steps.w & 8) != 0;
  float uniformStep = max(total / float(viewSteps), 1e-3);
  float baseStep = max(cloud.stepGrowth.x, 1e-3);
  float growthStart = max(cloud.stepGrowth.y, 1.0);
  float maxFactor = cloud.stepGrowth.z;
  uint viewCount = 0u, lightCount = 0u;
  ivec2 blueSize = textureSize(blueNoise, 0);
  float xi = jitter ? texelFetch(blueNoise, pixel % blueSize, 0).r : 0.5;
  float phaseOctave[8];
  for (int o = 0; o < octaves; ++o)
    phaseOctave[o] = cloudPhase(cloud.phase.x * cloudOctaveEccentricityScale(c, o), cloud.phase.y * cloudOctaveEccentricityScale(c, o), cloud.phase.z, nu);

  float transmittance = 1.0;
  vec3 sunlike = vec3(0.0);  // cloud light with the sun's spectrum, at the batch's wavelengths
  vec3 skylike = vec3(0.0);  // cloud light with the sky's spectrum
  float depthSum = 0.0, depthWeight = 0.0;
  // Hard cap on samples (segment ends add partial steps). Growing steps: a stretch [t0, t1] takes
  // N (1 + ln(G)) + N (t1 - G D) / (G D) steps at most (common/cloud_march.glsl); with t1 <= 80 km and
  // D >= 1 km that stays below ~8 N for G >= 10, hence 8 N.
  int budget = (uniformSteps ? 4 : 8) * viewSteps + 64;
  for (int s = 0; s < count && transmittance > earlyExit && budget > 0; ++s) {
    CloudLayer layer = layerAt(segmentLayer[s]);
    float t = segments[s].x;
    float end = segments[s].y;
    int emptyRun = coarse;  // start in coarse mode
    while (t < end && transmittance > earlyExit && budget > 0) {
      --budget;
      float dt = uniformSteps ? uniformStep : cloudViewStep(t, baseStep, growthStart, maxFactor);
      if (emptyRun >= coarse && coarse > 1) {
        // Coarse step: the shape-only density at one point of the next `coarse` fine steps.
        float span = min(float(coarse) * dt, end - t);
        CloudLayer column;
        float ph;
        vec3 local;
        ++viewCount;
        if (shapeDensityAt(layer, origin + dir * (t + xi * span), column, ph, local) <= 0.0) {
          t += span;
          continue;
        }
        emptyRun = 0;  // cloud ahead: march this stretch in fine steps
      }
      float h = min(dt, end - t);
      vec3 p = origin + dir * (t + xi * h);
      float d = densityAt(layer, p);
      ++viewCount;
      if (d <= 0.0) {
        ++emptyRun;
        t += h;
        continue;
      }
      emptyRun = 0;
      float sigmaT = layer.extinction * d;
      float sigmaS = albedo * sigmaT;
      float rp = length(p);
      float muS = dot(p, sun) / rp;
      float ph = cloudHeightFraction(layer, rp);
      // Sun: atmosphere transmittance at the sample, cloud optical depth by the light march.
      vec3 sunLight = transmittanceToSun(transmittanceLut, atmosphere, rp, muS) * atmosphere.solar_irradiance;
      bool sunVisible = max(sunLight.x + sunLight.y + sunLight.z, 0.0) > 0.0;
      float tau = sunVisible ? opticalDepthToSun(layer, p, sun, lightSteps, lightLength, cone) : 0.0;
      if (sunVisible) lightCount += uint(lightSteps);
      float octaveSum = 0.0;
      for (int o = 0; o < octaves; ++o)
        octaveSum += cloudOctaveWeight(b, o) * phaseOctave[o] * exp(-cloudOctaveExtinctionScale(a, o) * tau);
      vec3 sunSource = sunLight * octaveSum;
      vec3 skySource = vec3(0.0);
      if (ambientOn) {
        // Ambient: (L_sky v_sky + L_ground v_ground) / 2 (common/cloud_lighting.glsl).
        vec3 skyIrradiance = irradianceLookup(skyIrradianceLut, atmosphere, rp, muS);
        float rg = atmosphere.bottom_radius;
        vec3 groundSun = transmittanceToSun(transmittanceLut, atmosphere, rg, muS) * atmosphere.solar_irradiance * max(muS, 0.0);
        vec3 groundSky = irradianceLookup(skyIrradianceLut, atmosphere, rg, muS);
        float vSky = cloudSkyVisibility(ph, bottomVisibility);
        float vGround = cloudGroundVisibility(ph, bottomVisibility);
        vec3 reflectance = atmosphere.ground_albedo / kPi;
        skySource = 0.5 * (vSky * skyIrradiance / kPi + vGround * reflectance * groundSky);
        sunSource += 0.5 * vGround * reflectance * groundSun;
      }
      float integral = cloudStepIntegral(sigmaT, h);
      sunlike += transmittance * sigmaS * sunSource * integral;
      skylike += transmittance * sigmaS * skySource * integral;
      float stepT = exp(-sigmaT * h);
      float opacity = transmittance * (1.0 - stepT);
      depthSum += opacity * (t + 0.5 * h);
      depthWeight += opacity;
      transmittance *= stepT;
      t += h;
    }
  }

  // 4. Aerial perspective to the cloud's mean depth.
  vec3 airSky = vec3(0.0), airSun = vec3(0.0), airT = vec3(1.0);
  if (aerial && depthWeight > 0.0) airToDepth(atmosphere, origin, dir, sun, depthSum / depthWeight, airSky, airSun, airT);
  float opacity = 1.0 - transmittance;
  vec3 light = skyRadianceToRgb() * (airT * skylike + opacity * airSky) + sunRadianceToRgb() * (airT * sunlike + opacity * airSun);

  // 5. Composite.
  if (push.firstBatch != 0) {
    atomicAdd(counters.viewSamples, viewCount);
    atomicAdd(counters.lightSamples, lightCount);
    imageStore(cloudImage, pixel, vec4(light, transmittance));
    imageStore(skyImage, pixel, vec4(skyValue.rgb * transmittance + light, skyValue.a));
  } else {
    vec4 previous = imageLoad(cloudImage, pixel);
    imageStore(cloudImage, pixel, vec4(previous.rgb + light, previous.a));
    imageStore(skyImage, pixel, vec4(skyValue.rgb + light, skyValue.a));
  }
}
