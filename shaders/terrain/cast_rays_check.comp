#version 450
#extension GL_GOOGLE_include_directive : require
// The GPU ray cast on rays a test gives (tests/sky/test_terrain_pass.cpp): per ray two vec4 in
// (origin, r), (direction, mu), out (normal, t), (height, surface, 0, 0).
#define TERRAIN_BLOCK_BINDING 0
#define TERRAIN_HEIGHTS_BINDING 1
#define TERRAIN_PYRAMID_BINDING 2
#include "terrain/terrain_cast.glsl"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 3) readonly buffer Rays { vec4 v[]; } rays;
layout(std430, set = 0, binding = 4) writeonly buffer Hits { vec4 v[]; } hits;
layout(push_constant) uniform Push { uint count; } push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  vec4 a = rays.v[2u * i], b = rays.v[2u * i + 1u];
  TerrainCastHit hit = terrainCast(a.xyz, b.xyz, a.w, b.w, 0.0, kTerrainInfinity);
  hits.v[2u * i] = vec4(hit.normal, hit.t);
  hits.v[2u * i + 1u] = vec4(hit.height, float(hit.surface), 0.0, 0.0);
}
