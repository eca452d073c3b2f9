#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's ray cast, once per pixel (sky/terrain_pass.h): the camera ray against the height field
// (terrain/terrain_cast.glsl), then at the hit the sun's visibility past the terrain (a shadow ray in
// the height field) and the clouds' optical depth along the sun line (their Beer shadow map,
// common/cloud_shadow.glsl), and the share of the sky the terrain leaves it (the horizon map's slices,
// common/terrain_sky_visibility.glsl, or occlusion rays). Writes, per pixel, the hit for
// terrain/shade_terrain (per spectral batch) and the depth that the cloud march stops at (1e30 where
// the ray meets no terrain).
#include "common/camera.glsl"
#include "common/cloud_shadow.glsl"
#include "common/dispatch.glsl"
#include "common/terrain_sky_visibility.glsl"
#define TERRAIN_BLOCK_BINDING 0
#define TERRAIN_HORIZON_BINDING 6
#define TERRAIN_HEIGHTS_BINDING 1
#define TERRAIN_PYRAMID_BINDING 2
#include "terrain/terrain_cast.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
// Three vec4 per pixel: (normal, t), (sun visibility past the terrain, cloud optical depth to the sun,
// height, sky visibility), (the deck's diffuse sunlight D, its transmission of sky light T_d, the level
// of detail at the hit, 0);
// t = 1e30 where the ray meets no terrain. Sky visibility: the cosine-weighted share of the sky the
// surface sees (the isotropic (1 + n.z) / 2 without the terrain's occlusion).
layout(std430, set = 0, binding = 3) writeonly buffer TerrainHits { vec4 v[]; }
hits;
layout(std430, set = 0, binding = 4) writeonly buffer TerrainDepth { float t[]; }
depth;
layout(set = 0, binding = 5) uniform sampler2D cloudShadowMap;  // linear, clamp; 1x1 and unread without clouds
layout(push_constant) uniform Push { TileDispatch tiles; }
push;

// Eddington's total (direct + diffuse) transmission of a conservative slab of optical depth tau with
// asymmetry g for light arriving at cosine mu0 (Shettle & Weinman 1970): 1 at tau = 0.
float deckTransmission(float tau, float g, float mu0) {
  float scaled = (1.0 - g) * tau;
  return ((2.0 / 3.0 + mu0) + (2.0 / 3.0 - mu0) * exp(-tau / mu0)) / (4.0 / 3.0 + scaled);
}

// The deck's (diffuse sunlight, transmission of sky light) under a slab of vertical optical depth tauV:
// D = T(tauV, mu_s) - e^(-tauV / mu_s) (the direct beam is the shadow's), T_d = T(tauV, 1/2).
vec2 deckDiffuse(float tauV, float g, float mu0) {
  return vec2(max(deckTransmission(tauV, g, mu0) - exp(-tauV / mu0), 0.0), min(deckTransmission(tauV, g, 0.5), 1.0));
}

// The cosine-weighted share of the sky seen at p (normal n, inside the grid) past the horizons of the
// map (bilinear between texels per azimuth): (2 / A) sum_k slice_k (common/terrain_sky_visibility.glsl).
float horizonSkyVisibility(vec3 p, vec3 up, vec3 n, float R) {
  vec2 plane = terrainPlanePoint(p, R);
  int w = terrain.horizon_size.x, h = terrain.horizon_size.y, azimuths = terrain.horizon_size.z;
  vec2 g = clamp((plane - terrain.horizon_grid.xy) / terrain.horizon_grid.zw, vec2(0.0), vec2(w - 1, h - 1));
  int i = min(int(g.x), w - 2), j = min(int(g.y), h - 2);
  vec2 f = g - vec2(i, j);
  int k00 = (j * w + i) * azimuths, k10 = k00 + azimuths, k01 = k00 + w * azimuths, k11 = k01 + azimuths;
  vec4 weights = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
  // The plane's east and north at p (the gnomonic plane's axes, turned into p's tangent plane).
  vec3 east = normalize(vec3(1.0, 0.0, 0.0) - up * up.x);
  vec3 north = cross(up, east);
  float c0 = dot(n, east), s0 = dot(n, north), nz = dot(n, up);
  float sum = 0.0;
  for (int k = 0; k < azimuths; ++k) {
    float phi = 6.28318531 * (float(k) + 0.5) / float(azimuths);
    float alpha = weights.x * terrainHorizons.v[k00 + k] + weights.y * terrainHorizons.v[k10 + k] +
                  weights.z * terrainHorizons.v[k01 + k] + weights.w * terrainHorizons.v[k11 + k];
    sum += terrainSkySlice(alpha, c0 * cos(phi) + s0 * sin(phi), nz);
  }
  return clamp(2.0 * sum / float(azimuths), 0.0, 1.0);
}

// The same share from `count` rays cosine-weighted about n (an equal-area spiral turned by a per-pixel
// angle): the share of them that leave the terrain.
float raySkyVisibility(vec3 p, vec3 up, vec3 n, int count, uvec2 pixel, TerrainLodRay lod) {
  vec3 a = normalize(cross(abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0), n));
  vec3 b = cross(n, a);
  uint seed = pixel.x * 1973u + pixel.y * 9277u + 26699u;
  seed = (seed ^ (seed >> 16)) * 0x7feb352du;
  seed = (seed ^ (seed >> 15)) * 0x846ca68bu;
  float turn = 6.28318531 * float(seed >> 8) / 16777216.0;
  vec3 start = p + 2.0 * n + 0.5 * up;
  float rs = length(start);
  int open = 0;
  for (int k = 0; k < count; ++k) {
    float u = (float(k) + 0.5) / float(count);
    float radius = sqrt(u), angle = 2.39996323 * float(k) + turn;
    vec3 d = normalize(radius * cos(angle) * a + radius * sin(angle) * b + sqrt(1.0 - u) * n);
    TerrainCastHit blocker =
        terrainCastLod(start, d, rs, clamp(dot(start, d) / rs, -1.0, 1.0), 0.0, kTerrainInfinity, lod);
    if (!(blocker.hit && blocker.t > 1.0)) ++open;
  }
  return float(open) / float(count);
}

void main() {
  uvec2 tile_pixel;
  if (!tilePixel(push.tiles, tile_pixel)) return;
  uint index = tile_pixel.y * push.tiles.width + tile_pixel.x;
  CameraParameters camera =
      cameraFromBlock(terrain.camera_forward, terrain.camera_right, terrain.camera_up, terrain.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(tile_pixel) + 0.5, valid);
  TerrainCastHit hit = terrainNoHit();
  vec3 origin = terrain.camera_position.xyz;
  float R = terrain.camera_position.w;
  // Level of detail: the pixel's cone, terrain.lod.x field cells wide per metre of distance.
  TerrainLodRay cameraLod = TerrainLodRay(0.0, terrain.lod.x);
  if (valid) {
    float r = length(origin);
    float mu = clamp(dot(origin, dir) / r, -1.0, 1.0);
    hit = terrainCastLod(origin, dir, r, mu, 0.0, kTerrainInfinity, cameraLod);
  }
  float lambda = hit.hit ? terrainLodLevel(cameraLod, hit.t) : 0.0;
  // The shadow and occlusion rays meet the surface the camera sees at the hit: its level, kept along them.
  TerrainLodRay pointLod = TerrainLodRay(terrain.lod.x * (hit.hit ? hit.t : 0.0), 0.0);
  float visibility = 1.0;
  float cloudDepth = 0.0;
  float skyVisibility = 1.0;
  vec2 deck = vec2(0.0, 1.0);
  if (hit.hit) {
    vec3 sun = terrain.sun_direction.xyz;
    vec3 p = origin + dir * hit.t;
    vec3 up = normalize(p);
    // Field points shade with the smooth normal (the cast's exact one stays for walls and the outside).
    if (hit.surface == 1) {
      vec2 plane = terrainPlanePoint(p, R);
      vec3 smoothNormal = terrainLodSmoothNormal(plane, lambda, R);
      if (dot(smoothNormal, smoothNormal) > 0.5) hit.normal = smoothNormal;
    }
    skyVisibility = 0.5 * (1.0 + clamp(dot(hit.normal, up), -1.0, 1.0));
    if (terrain.sky_occlusion.x == 1 && hit.surface == 1) skyVisibility = horizonSkyVisibility(p, up, hit.normal, R);
    if (terrain.sky_occlusion.x == 2)
      skyVisibility = raySkyVisibility(p, up, hit.normal, terrain.sky_occlusion.y, tile_pixel, pointLod);
    // The shadow ray starts 2 m out along the normal and 0.5 m up: the hit's float position is good to
    // ~0.5 m at the planet's radius, and a start under the surface would shadow the point itself.
    if (terrain.sun_direction.w > 0.5 && dot(hit.normal, sun) > 0.0 && dot(up, sun) > -0.1) {
      vec3 start = p + 2.0 * hit.normal + 0.5 * up;
      float rs = length(start);
      float mus = clamp(dot(start, sun) / rs, -1.0, 1.0);
      TerrainCastHit blocker = terrainCastLod(start, sun, rs, mus, 0.0, kTerrainInfinity, pointLod);
      if (blocker.hit && blocker.t > 1.0) visibility = 0.0;
    }
    if (terrain.shadow_v.w > 0.5) {
      vec3 c = cloudShadowCoordinate(p, terrain.shadow_centre.xyz, terrain.shadow_u.xyz, terrain.shadow_v.xyz, sun,
                                     terrain.shadow_centre.w, terrain.shadow_u.w);
      if (cloudShadowCovers(c)) {
        // Penumbra: the sun's disc (tan of its radius in heights.w) seen from p covers, on the map's
        // plane through the layers' middle (perpendicular to the sun, depth L), a disc of radius
        // (depth(p) - L) tan(radius): 8 lookups over it (Vogel's equal-area spiral), their
        // transmittances averaged. With clouds at height h over the ground that is a penumbra
        // 2 h tan(0.265 deg) wide (9.3 m per km) for a sun at the zenith, 1 / mu_s times more across the
        // sun's azimuth. Off (heights.w = 0): one lookup.
        float reach = terrain.heights.w * max(c.z - terrain.shadow_u.w, 0.0) / terrain.shadow_centre.w;
        float transmittance = 0.0;
        for (int k = 0; k < 8; ++k) {
          float radius = reach * sqrt((float(k) + 0.5) / 8.0);
          float angle = 2.39996323 * float(k);
          vec2 at = c.xy + radius * vec2(cos(angle), sin(angle));
          transmittance += exp(-cloudShadowOpticalDepth(textureLod(cloudShadowMap, at, 0.0), c.z));
        }
        cloudDepth = -log(max(transmittance / 8.0, 1.0e-30));
      }
      // The deck's diffuse light: the slab of the point's own column (tau_v = tau mu_s), or
      // (deck.y) the mean over 8 directions cosine-weighted about the zenith (an equal-area spiral:
      // sin(theta) = sqrt((k + 1/2) / 8)) of the slab of the column each meets at the clouds' middle
      // height (its tau_max along the sun line in the map): a shadow beside clear sky gets the gaps'
      // light and less of the clouds' diffuse sunlight, a lit point beside clouds some of it.
      float mu0 = max(dot(up, sun), 0.05);
      float g = terrain.albedo_rock.w;
      deck = deckDiffuse(cloudDepth * mu0, g, mu0);
      float above = terrain.deck.x - length(p);
      if (terrain.deck.y > 0.5 && above > 0.0) {
        vec3 east = normalize(cross(vec3(0.0, 1.0, 0.0), up));
        vec3 north = cross(up, east);
        vec2 sum = vec2(0.0);
        for (int k = 0; k < 8; ++k) {
          float sine = sqrt((float(k) + 0.5) / 8.0), angle = 2.39996323 * float(k);
          float cosine = sqrt(1.0 - sine * sine);
          vec3 d = sine * (cos(angle) * east + sin(angle) * north) + cosine * up;
          vec3 q = p + d * (above / cosine);
          vec3 cq = cloudShadowCoordinate(q, terrain.shadow_centre.xyz, terrain.shadow_u.xyz, terrain.shadow_v.xyz, sun,
                                          terrain.shadow_centre.w, terrain.shadow_u.w);
          float tauColumn = cloudShadowCovers(cq) ? textureLod(cloudShadowMap, cq.xy, 0.0).z : cloudDepth;
          sum += deckDiffuse(tauColumn * mu0, g, mu0);
        }
        deck = sum / 8.0;
      }
    }
    if (terrain.heights.z > 0.5) deck = vec2(0.0, 1.0);  // the clear-sky table alone
  }
  hits.v[3u * index] = vec4(hit.normal, hit.t);
  hits.v[3u * index + 1u] = vec4(visibility, cloudDepth, hit.height, skyVisibility);
  hits.v[3u * index + 2u] = vec4(deck, lambda, 0.0);
  depth.t[index] = hit.t;
}
