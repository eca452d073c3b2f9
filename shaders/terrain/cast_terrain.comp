#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's ray cast, once per pixel (sky/terrain_pass.h): the camera ray against the height field
// (terrain/terrain_cast.glsl), then at the hit the sun's visibility past the terrain (a shadow ray in
// the height field) and the clouds' optical depth along the sun line (their Beer shadow map,
// common/cloud_shadow.glsl). Writes, per pixel, the hit for terrain/shade_terrain (per spectral batch)
// and the depth that the cloud march stops at (1e30 where the ray meets no terrain).
#include "common/camera.glsl"
#include "common/cloud_shadow.glsl"
#include "common/dispatch.glsl"
#define TERRAIN_BLOCK_BINDING 0
#define TERRAIN_HEIGHTS_BINDING 1
#define TERRAIN_PYRAMID_BINDING 2
#include "terrain/terrain_cast.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
// Two vec4 per pixel: (normal, t), (sun visibility past the terrain, cloud optical depth to the sun,
// height, surface); t = 1e30 where the ray meets no terrain.
layout(std430, set = 0, binding = 3) writeonly buffer TerrainHits { vec4 v[]; }
hits;
layout(std430, set = 0, binding = 4) writeonly buffer TerrainDepth { float t[]; }
depth;
layout(set = 0, binding = 5) uniform sampler2D cloudShadowMap;  // linear, clamp; 1x1 and unread without clouds
layout(push_constant) uniform Push { TileDispatch tiles; }
push;

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
  if (valid) {
    float r = length(origin);
    float mu = clamp(dot(origin, dir) / r, -1.0, 1.0);
    hit = terrainCast(origin, dir, r, mu, 0.0, kTerrainInfinity);
  }
  float visibility = 1.0;
  float cloudDepth = 0.0;
  if (hit.hit) {
    vec3 sun = terrain.sun_direction.xyz;
    vec3 p = origin + dir * hit.t;
    vec3 up = normalize(p);
    // Field points shade with the smooth normal (the cast's exact one stays for walls and the outside).
    if (hit.surface == 1) {
      vec2 plane = terrainPlanePoint(p, R);
      vec3 smoothNormal = terrainSmoothNormal(plane, R);
      if (dot(smoothNormal, smoothNormal) > 0.5) hit.normal = smoothNormal;
    }
    // The shadow ray starts 2 m out along the normal and 0.5 m up: the hit's float position is good to
    // ~0.5 m at the planet's radius, and a start under the surface would shadow the point itself.
    if (terrain.sun_direction.w > 0.5 && dot(hit.normal, sun) > 0.0 && dot(up, sun) > -0.1) {
      vec3 start = p + 2.0 * hit.normal + 0.5 * up;
      float rs = length(start);
      float mus = clamp(dot(start, sun) / rs, -1.0, 1.0);
      TerrainCastHit blocker = terrainCast(start, sun, rs, mus, 0.0, kTerrainInfinity);
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
    }
  }
  hits.v[2u * index] = vec4(hit.normal, hit.t);
  hits.v[2u * index + 1u] = vec4(visibility, cloudDepth, hit.height, float(hit.surface));
  depth.t[index] = hit.t;
}
