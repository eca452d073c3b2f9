// cloud_sampling.glsl: the cloud block and the density lookups shared by the cloud shaders
// (render_clouds.comp, bake_shadow_map.comp): the layers, the noise and weather textures, and the
// density at a point (common/cloud_density.glsl on the textures, common/cloud_weather.glsl columns).
#ifndef FIRMAMENT_CLOUD_SAMPLING_GLSL
#define FIRMAMENT_CLOUD_SAMPLING_GLSL

#include "common/cloud_density.glsl"
#include "common/cloud_lighting.glsl"
#include "common/cloud_weather.glsl"

layout(set = 0, binding = 4) uniform sampler3D shapeNoise;   // linear, repeat
layout(set = 0, binding = 5) uniform sampler3D detailNoise;  // linear, repeat
layout(set = 0, binding = 6) uniform sampler2D curlNoise;    // linear, repeat
// Every knob of clouds/cloud_march_knobs.def as a float, in the table's order (clouds/cloud_block.cpp
// fills the same struct from the same table): a term reads its knob as cloud.knobs.NAME.
struct CloudKnobs {
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) float name;
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
};
// A layer in the block (std140: 5 vec4, 80 bytes; clouds/cloud_block.cpp fills the same struct): the
// shared CloudLayer's fields (common/cloud_density.glsl) and the layer's octave parameters a, b, c.
struct CloudBlockLayer {
  float bottomRadius; float topRadius; float coverage; float extinction;
  float densityScale; float anvil; float shapePeriod; float detailPeriod;
  float detailStrength; float curlPeriod; float curlStrength; float msA;
  vec3 windOffset; float msB;
  vec2 skew; float kind; float msC;
};
// A layer's lighting (std140: one vec4): the diffusion floor's weight d (cloudEddingtonSlabSource; 0: off),
// the reflected light's r and a_r (cloudReflectedSource; r 0: off), the base's limb darkening
// (cloudBaseLimbFactor's strength).
struct CloudBlockLayerLighting {
  float floorWeight; float reflectWeight; float reflectDepthScale; float baseLimb;
};
layout(std140, set = 0, binding = 10) uniform CloudBlock {
  vec4 camera_position;  // planet-centred, m
  vec4 camera_forward;   // xyz; w = horizontal fov (rad)
  vec4 camera_right;     // xyz; w = yaw (rad)
  vec4 camera_up;        // xyz
  vec4 sun_direction;    // xyz; w = largest march distance (m)
  ivec4 image;           // width, height, projection, layer count
  ivec4 steps;           // view steps, light steps, octaves, flags (1 unused: the aerial perspective is a compile-time variant, 2 jitter, 4 ambient, 8 uniform steps, 16 light march to the layer exit, 32 octaves >= 1 also from the top, 64 octaves >= 1 scattered part only, 128 light steps per thickness, 256 light through the other layers, 512 the early exit's remainder)
  vec4 phaseLight;       // x: the second phase lobe's Draine alpha; y: δ-scaled share f (CloudMarchSettings::deltaScaling); z: unused; w: light march length (m; the largest one with flag 16)
  vec4 phase;            // phase lobes g1, g2, second lobe's weight w (cloudPhase), single-scattering albedo
  vec4 march;            // ambient bottom visibility, unused, coarse factor, unused (knobs.earlyExitTransmittance, knobs.lightCone)
  vec4 stepGrowth;       // base step h0 (m), growth start D (m), largest step factor G, unused (knobs.emptySpaceMargin)
  vec4 weatherRegion;    // weather map: width (m), height (m), skew east, skew north (m per m)
  vec4 weatherPlanet;    // x: planet (ground) radius (m); y, z: the view step's growth behind dense cloud T1, K (cloudLowTransmittanceStepFactor); w: the other layers' light-step scale
  vec4 shadowCentre;     // Beer shadow map: centre C (cloud frame, m); w = extent (m, square side)
  vec4 shadowAxisU;      // xyz: unit axis u (perpendicular to the sun); w = start distance L (m)
  vec4 shadowAxisV;      // xyz: unit axis v; w = march length (m)
  ivec4 shadowSize;      // texels per side, march steps, enabled (the light march reads it), unused
  vec4 aerial;           // aerial perspective: the volume's maximum distance D (m), the air march's steps; z: noise LOD scale (CloudMarchSettings::noiseLodScale); w: unused
  CloudBlockLayer layers[8];                  // per layer (CloudBlockLayer)
  CloudBlockLayerLighting layerLighting[8];   // per layer (CloudBlockLayerLighting)
  vec4 weatherReach;     // x: radius (m) of the coverage reach map (0: none); y: the longest coarse span on it (m)
  vec4 otherLayerMap;    // the other layers' map (clouds/other_layer_map.glsl): log-warp scale ln(1 + E / rho0), rho0 (m), texels per side, tiles (0: none)
  vec4 otherLayerOrigin; // its plane's origin c (cloud frame, m); w: the first row the bake writes
  vec4 otherLayerAxisU;  // its axis u; w: the bake writes every w-th row from the first
  vec4 otherLayerAxisV;  // its axis v
  vec4 otherLayerSun;    // the sun direction its lines follow (the sun of its last full bake)
  vec4 columnMap;        // the column map (clouds/column_map.glsl): log-warp scale ln(1 + E / rho0), rho0 (m), texels per side, levels K (0: none)
  vec4 columnOrigin;     // its unit normal c at the camera's ground point; w: the first row the bake writes
  vec4 columnAxisU;      // its axis u; w: the bake writes every w-th row from the first
  vec4 columnAxisV;      // its axis v; w: the planet radius R of its projection (m)
  vec4 deepShadowMap;    // the deep shadow map (clouds/deep_shadow_map.glsl; placed as the other layers' map): texels per side, levels K, near light steps, baked (0: no map)
  vec4 buildUp;          // x: the higher orders' build-up along the view, k (CloudMarchSettings::msBuildUpScale; 0: off); y: 1 for the ambient as a slab (CloudMarchSettings::ambientSlab); z: 1 where the column map's ambient slices are baked this frame (the slab through the other layers: ambientThroughOtherLayers, more than one layer, the column map); w: the slab's flow towards the camera (ambientFlow)
  vec4 layerLowSun[2];   // per layer (4 a vec4): the octaves' and the reflected light's low-sun scale min(1, mu_s / mu_0), mu_0 (CloudLayerSettings::msLowSunMu, or CloudMarchSettings::octaveLowSunMu for all; 0: off)
  CloudKnobs knobs;      // every knob by name (clouds/cloud_march_knobs.def)
} cloud;

// δ-scaled transport (CloudMarchSettings::deltaScaling): the phase peak's share f goes straight on,
// so light paths see sigma_t' = (1 - f omega) sigma_t; 1 without a peak.
float cloudLightTransportScale() { return 1.0 - cloud.phaseLight.y * cloud.phase.w; }

// The phase's mean cosine as the light paths see it (the diffusion floor, the ambient's slab). With
// δ-scaling the scaled medium's phase keeps the rest after the peak's share f went straight on:
// g = f + (1 - f) g', so g' = (g - f) / (1 - f) (f = 0: unchanged).
float cloudLightPhaseMeanCosine() {
  float peakShare = cloud.phaseLight.y;
  return (cloudPhaseMeanCosine(cloud.phase.x, cloud.phase.y, cloud.phase.z, cloud.phaseLight.x) - peakShare) / max(1.0 - peakShare, 1e-3);
}

layout(set = 0, binding = 12) uniform sampler2D weatherMap;  // linear, repeat (common/cloud_weather.glsl)


CloudLayer layerAt(int i) {
  CloudBlockLayer l = cloud.layers[i];
  CloudLayer layer;
  layer.bottom_radius = l.bottomRadius;
  layer.top_radius = l.topRadius;
  layer.coverage = l.coverage;
  layer.extinction = l.extinction;
  layer.density_scale = l.densityScale;
  layer.anvil = l.anvil;
  layer.shape_period = l.shapePeriod;
  layer.detail_period = l.detailPeriod;
  layer.detail_strength = l.detailStrength;
  layer.curl_period = l.curlPeriod;
  layer.curl_strength = l.curlStrength;
  layer.wind_offset = l.windOffset;
  layer.skew = l.skew;
  layer.kind = int(l.kind + 0.5);
  layer.stratiform = 0.0;  // set per column by cloudColumnLayer
  layer.stratiform_kind = kCloudStratus;
  return layer;
}

// A layer's texel sizes in metres (x: shape, y: detail), for noiseLod.
vec2 noiseTexels(CloudLayer layer) {
  return vec2(layer.shape_period / float(textureSize(shapeNoise, 0).x), layer.detail_period / float(textureSize(detailNoise, 0).x));
}

// The mip levels (x: shape, y: detail) for a lookup whose footprint is `footprint` metres: log2 of the
// footprint in texels (noiseTexels) of each texture, at least 0 (CloudMarchSettings::noiseLodScale;
// footprint 0: level 0). The sampler takes the nearest level.
vec2 noiseLod(vec2 texels, float footprint) {
  if (!(footprint > 0.0)) return vec2(0.0);
  return max(log2(vec2(footprint) / texels), vec2(0.0));
}

// Light-march samples for a way of `length_m` through a layer `thickness_m` thick: lightSteps per
// thickness of the way, from `minimum` to 4 lightSteps (a grazing sun's long way gets more samples).
int lightStepsForLength(int lightSteps, float length_m, float thickness_m, int minimum) {
  return clamp(int(ceil(float(lightSteps) * length_m / max(thickness_m, 1.0))), minimum, 4 * lightSteps);
}

// p's texture coordinate on the weather map (and its coverage reach) for `layer` (common/cloud_weather.glsl).
vec2 weatherCoordinateAt(CloudLayer layer, vec3 p) {
  return cloudWeatherCoordinate(p, cloud.weatherPlanet.x, cloud.weatherRegion.xy, cloud.weatherRegion.zw, layer.wind_offset);
}

// The shape-only density SN_nd at p before its clamp (cloudShapeSignedDensity: -1 outside the shell or
// where the weather map has no cloud, <= 0 outside the shape); the weather map's column layer, ph and
// local are returned for the detail.
// lod: the mip levels of the shape and detail lookups (x, y; noiseLod; 0: level 0).
float shapeSignedDensityAt(CloudLayer layer, vec3 p, vec2 lod, out CloudLayer column, out float ph, out vec3 local) {
  float r = length(p);
  column = layer;
  local = vec3(0.0);
  ph = cloudHeightFraction(layer, r);
  if (ph <= 0.0 || ph >= 1.0) return -1.0;
  float planet = cloud.weatherPlanet.x;
  vec4 weather = textureLod(weatherMap, weatherCoordinateAt(layer, p), 0.0);
  bool empty;
  column = cloudColumnLayer(layer, weather, planet, empty);
  if (empty) return -1.0;
  ph = cloudHeightFraction(column, r);
  if (ph <= 0.0 || ph >= 1.0) return -1.0;
  local = cloudLocalPosition(column, p);
  vec4 shape = textureLod(shapeNoise, cloudShapeCoordinate(column, local), lod.x);
  return cloudShapeSignedDensity(column, ph, shape, weather.x);
}

// The shape-only density SN_nd at p (0 outside the shell or where the weather map has no cloud).
float shapeDensityAt(CloudLayer layer, vec3 p, vec2 lod, out CloudLayer column, out float ph, out vec3 local) {
  return max(shapeSignedDensityAt(layer, p, lod, column, ph, local), 0.0);
}

// The full density d from the shape-only density `base` and what shapeSignedDensityAt returned with it.
float densityFromShape(CloudLayer column, float ph, vec3 local, float base, vec2 lod) {
  if (base <= 0.0) return 0.0;
  vec2 curl = textureLod(curlNoise, cloudCurlCoordinate(column, local), 0.0).xy;
  vec4 detail = textureLod(detailNoise, cloudDetailCoordinate(column, local, curl, ph), lod.y);
  return cloudDensity(column, ph, base, detail);
}

// The full density d at p.
float densityAt(CloudLayer layer, vec3 p, vec2 lod) {
  CloudLayer column;
  float ph;
  vec3 local;
  float base = shapeDensityAt(layer, p, lod, column, ph, local);
  return densityFromShape(column, ph, local, base, lod);
}

// Optical depth towards the sun (or any unit direction `sun`) from p through `layer`, over `length_m`
// split into n steps growing quadratically (boundaries L (j/n)^2), each sampled at the midpoint of its
// span. Each sample is pushed sideways within a cone of half-angle atan(cone) by a fixed kernel
// (Schneider 2015's cone sampling, deterministic here; only the bench's first-milestone rows use it).
// Only the first `taken` steps are marched (n: all; fewer: the rest comes from the deep shadow map,
// clouds/deep_shadow_map.glsl, from L (taken / n)^2 on).
float opticalDepthToSunTaken(CloudLayer layer, vec3 p, vec3 sun, int n, int taken, float length_m, float cone, vec2 lod) {
  const vec2 kernel[6] = vec2[6](vec2(0.38, 0.92), vec2(-0.84, 0.28), vec2(0.59, -0.70), vec2(-0.15, -0.48),
                                 vec2(0.95, 0.05), vec2(-0.45, 0.62));
  // Without a cone (a compile-time 0 in the march's specialization) the sideways part is compiled out.
  vec3 t1 = vec3(0.0), t2 = vec3(0.0);
  if (cone > 0.0) {
    t1 = normalize(abs(sun.z) < 0.9 ? cross(sun, vec3(0.0, 0.0, 1.0)) : cross(sun, vec3(1.0, 0.0, 0.0)));
    t2 = cross(sun, t1);
  }
  float tau = 0.0;
  float previous = 0.0;
  taken = min(taken, n);
  for (int g = 0; g < taken; ++g) {
    float f = float(g + 1) / float(n);
    float next = length_m * f * f;
    float mid = 0.5 * (previous + next);
    vec3 q = p + sun * mid;
    if (cone > 0.0) {
      vec2 k = kernel[g % 6] * cone * mid;
      q = q + t1 * k.x + t2 * k.y;
    }
    tau += layer.extinction * densityAt(layer, q, lod) * (next - previous);
    previous = next;
  }
  return tau;
}

// The same with every one of the n steps sampled.
float opticalDepthToSun(CloudLayer layer, vec3 p, vec3 sun, int n, float length_m, float cone, vec2 lod) {
  return opticalDepthToSunTaken(layer, p, sun, n, n, length_m, cone, lod);
}

// Optical depth of every layer but `own` along the sun ray from p (radius r, mu_s = cos of the sun's
// zenith at p), up to maxLength: a deck above shadows the one below (docs/clouds.md "Light through
// other layers"). Each stretch the ray spends in another shell gets lightSteps equal steps per layer
// thickness of its length, 2 to 4 lightSteps (the sample's own layer's rate: half of it left the
// midpoints too coarse for a deck's bump-shaped profile: -14.5 % at 6 light steps in a scratch run of
// CloudReference.ADeckAboveShadowsTheLayerBelow's scene). `count` adds the density evaluations.
float opticalDepthThroughOtherLayers(int own, vec3 p, float r, float muS, vec3 sun, int lightSteps, float maxLength,
                                     vec2 lod, inout uint count) {
  float tau = 0.0;
  // The other layers in order, without an iteration for `own`, and both stretches of a layer in one
  // loop: lavapipe runs a skipped iteration's code and an empty loop's body once anyway (docs/gpu.md).
  for (int j = 0; j + 1 < cloud.image.w; ++j) {
    int i = j < own ? j : j + 1;
    CloudLayer other = layerAt(i);
    vec2 first, second;
    cloudShellSegments(r, muS, other.bottom_radius, other.top_radius, maxLength, first, second);
    float thickness = other.top_radius - other.bottom_radius;
    float length1 = first.y - first.x, length2 = second.y - second.x;
    int n1 = length1 > 0.0 ? lightStepsForLength(lightSteps, length1, thickness, 2) : 0;
    int n2 = length2 > 0.0 ? lightStepsForLength(lightSteps, length2, thickness, 2) : 0;
    // n equal steps over each stretch, sampled at their midpoints.
    float h1 = n1 > 0 ? length1 / float(n1) : 0.0;
    float h2 = n2 > 0 ? length2 / float(n2) : 0.0;
    float sum1 = 0.0, sum2 = 0.0;
    for (int k = 0; k < n1 + n2; ++k) {
      bool inFirst = k < n1;
      float along = inFirst ? first.x + (float(k) + 0.5) * h1 : second.x + (float(k - n1) + 0.5) * h2;
      float density = densityAt(other, p + sun * along, lod);
      if (inFirst) sum1 += density;
      else sum2 += density;
    }
    if (n1 > 0) tau += other.extinction * h1 * sum1;
    if (n2 > 0) tau += other.extinction * h2 * sum2;
    count += uint(n1 + n2);
  }
  return tau;
}

#endif  // FIRMAMENT_CLOUD_SAMPLING_GLSL
