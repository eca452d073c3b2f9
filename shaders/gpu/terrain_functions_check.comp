#version 460
#extension GL_GOOGLE_include_directive : require
// Build-time check: the terrain's shared headers (common/terrain_geometry.glsl, terrain_albedo.glsl)
// compile as GLSL, so the GPU ray cast can call the functions the CPU walk and the tests use. Every
// function is called once on constants; no test dispatches it.
#include "common/terrain_geometry.glsl"
#include "common/terrain_albedo.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer B { float v[]; };
void main() {
  TerrainCellRay ray;
  ray.origin = vec3(0.0, 0.0, 6360100.0); ray.direction = vec3(0.0, 0.6, -0.8); ray.r = 6360100.0; ray.mu = -0.8; ray.planetRadius = 6360000.0;
  float t; bool hit = terrainCellHit(ray, vec4(0.0, 0.0, 10.0, 10.0), vec4(1.0, 2.0, 3.0, 4.0), 0.0, 200.0, 20, t);
  float a, b; bool bottom; bool s = terrainCellSpan(ray, 0.0, 10.0, 0.0, 1000.0, a, b, bottom);
  TerrainAlbedoParameters p; p.rock = vec3(0.2); p.vegetation = vec3(0.1); p.snow = vec3(0.9); p.treeLine = 2000.0; p.treeLineTransition = 100.0;
  p.vegetationMaxSlope = 0.6; p.snowLine = 3000.0; p.snowLineTransition = 100.0; p.snowMaxSlope = 0.9; p.slopeTransition = 0.1;
  vec3 n = terrainSurfaceNormal(vec2(1.0, 2.0), 100.0, vec2(0.1, 0.2), 6360000.0);
  v[0] = t + a + b + float(hit) + float(s) + float(bottom) + terrainAlbedo(2500.0, terrainSlopeCosine(vec2(1.0,2.0), n, 6360000.0), p).x + terrainCrossingX(ray.origin, ray.direction, 5.0, 6360000.0) + terrainPlaneStepX(ray.origin, ray.direction);
}
