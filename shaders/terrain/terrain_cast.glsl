// terrain_cast.glsl (GPU only): a ray against the height field on the curved planet, in float — the
// walk of terrain/terrain_intersection.cpp (TerrainIntersector::walk) line for line, with the same
// per-cell arithmetic (common/terrain_geometry.glsl, shared): the ray clipped to the sphere of the
// highest height and to the cone over the grid; outside it the sphere at the outside height in closed
// form; over the grid the min/max pyramid's quadtree walk (Tevs et al. 2008) down to the leaf cell's
// exact test (terrainCellHit, 20 halvings: float's resolution). The walk itself stays GLSL: its loop
// reads the pyramid through the buffers of terrain_block.glsl, which the CPU walk reads from its own
// classes (tests/sky/test_terrain_pass.cpp holds the two to the same hits).
//
// The ray is given as its origin (planet-centred, float) with its radius r and mu: a caller that knows
// an altitude exactly (the camera's, a ground point's) passes r = R + altitude rounded once, so the
// altitudes along the ray (terrainRayAltitude) are as exact as that float.
#ifndef FIRMAMENT_TERRAIN_CAST_GLSL
#define FIRMAMENT_TERRAIN_CAST_GLSL

#include "terrain/terrain_block.glsl"

struct TerrainCastHit {
  bool hit;
  float t;      // distance along the ray (m)
  vec3 normal;  // unit, outward
  float height; // surface height there (m above R)
  int surface;  // 0 none, 1 field, 2 wall, 3 outside (TerrainSurface)
};

const float kTerrainInfinity = 1.0e30;

// The bilinear height at a plane point clamped into the grid.
float terrainSampleClamped(vec2 plane, out vec4 cellHeights, out vec2 fraction) {
  int ncx = terrain.grid_size.x - 1, ncy = terrain.grid_size.y - 1;
  vec2 g = (plane - terrain.grid.xy) / terrain.grid.zw;
  int i = clamp(int(floor(g.x)), 0, ncx - 1);
  int j = clamp(int(floor(g.y)), 0, ncy - 1);
  fraction = clamp(g - vec2(i, j), 0.0, 1.0);
  cellHeights = terrainCellHeights(i, j);
  return terrainBilinear(cellHeights, fraction);
}

vec3 terrainFieldNormal(vec2 plane, float R) {
  vec4 heights;
  vec2 fraction;
  float h = terrainSampleClamped(plane, heights, fraction);
  vec2 gradient = terrainBilinearGradient(heights, fraction, terrain.grid.zw);
  return terrainSurfaceNormal(plane, h, gradient, R);
}

// The shading normal at a plane point inside the grid: the samples' central-difference gradients
// interpolated bilinearly (continuous across cells, where the bilinear surface's own gradient jumps:
// facets a camera near the ground sees as flat-shaded cells).
vec2 terrainVertexGradient(int i, int j) {
  int nx = terrain.grid_size.x, ny = terrain.grid_size.y;
  int i0 = max(i - 1, 0), i1 = min(i + 1, nx - 1), j0 = max(j - 1, 0), j1 = min(j + 1, ny - 1);
  return vec2((terrainAt(i1, j) - terrainAt(i0, j)) / (float(i1 - i0) * terrain.grid.z),
              (terrainAt(i, j1) - terrainAt(i, j0)) / (float(j1 - j0) * terrain.grid.w));
}

vec3 terrainSmoothNormal(vec2 plane, float R) {
  int ncx = terrain.grid_size.x - 1, ncy = terrain.grid_size.y - 1;
  vec2 g = (plane - terrain.grid.xy) / terrain.grid.zw;
  int i = clamp(int(floor(g.x)), 0, ncx - 1);
  int j = clamp(int(floor(g.y)), 0, ncy - 1);
  vec2 f = clamp(g - vec2(i, j), 0.0, 1.0);
  vec2 gradient = mix(mix(terrainVertexGradient(i, j), terrainVertexGradient(i + 1, j), f.x),
                      mix(terrainVertexGradient(i, j + 1), terrainVertexGradient(i + 1, j + 1), f.x), f.y);
  float h = terrainBilinear(terrainCellHeights(i, j), f);
  return terrainSurfaceNormal(plane, h, gradient, R);
}

TerrainCastHit terrainNoHit() {
  TerrainCastHit h;
  h.hit = false;
  h.t = kTerrainInfinity;
  h.normal = vec3(0.0, 0.0, 1.0);
  h.height = 0.0;
  h.surface = 0;
  return h;
}

TerrainCastHit terrainFinish(float t, int surface, vec3 normal, float height) {
  TerrainCastHit h;
  h.hit = true;
  h.t = t;
  h.surface = surface;
  h.normal = normal;
  h.height = height;
  return h;
}

// The first hit in [tMin, tMax] of the ray o + t d (d unit) with radius r and cosine mu at o.
TerrainCastHit terrainCast(vec3 o, vec3 d, float r, float mu, float tMin, float tMax) {
  float R = terrain.camera_position.w;
  bool hasOutside = terrain.grid_size.w != 0;
  float outsideHeight = terrain.heights.x;
  TerrainCellRay ray;
  ray.origin = o;
  ray.direction = d;
  ray.r = r;
  ray.mu = mu;
  ray.planetRadius = R;

  float shellNear, shellFar;
  if (!raySphereRoots(r, mu, R + terrain.heights.y, shellNear, shellFar) || shellFar < tMin) return terrainNoHit();
  float ta = max(tMin, shellNear);
  float tb = min(tMax, shellFar);
  if (!(ta <= tb)) return terrainNoHit();

  float X0 = terrain.grid.x, Y0 = terrain.grid.y;
  float X1 = X0 + float(terrain.grid_size.x - 1) * terrain.grid.z;
  float Y1 = Y0 + float(terrain.grid_size.y - 1) * terrain.grid.w;
  vec3 constraints[5] = vec3[5](vec3(R, 0.0, -X0), vec3(-R, 0.0, X1), vec3(0.0, R, -Y0), vec3(0.0, -R, Y1),
                                vec3(0.0, 0.0, 1.0));
  float coneEnter = -kTerrainInfinity, coneExit = kTerrainInfinity;
  int enterIndex = -1, exitIndex = -1;
  bool coneEmpty = false;
  for (int k = 0; k < 5; ++k) {
    float A = dot(constraints[k], o), B = dot(constraints[k], d);
    if (B == 0.0) {
      if (A < 0.0) coneEmpty = true;
    } else if (B > 0.0) {
      float t = -A / B;
      if (t > coneEnter) { coneEnter = t; enterIndex = k; }
    } else {
      float t = -A / B;
      if (t < coneExit) { coneExit = t; exitIndex = k; }
    }
  }
  float q0 = max(ta, coneEnter), q1 = min(tb, coneExit);
  coneEmpty = coneEmpty || !(q0 <= q1);

  // Outside the grid on [ta, q0] (or everywhere when the cone is missed).
  float p1 = coneEmpty ? tb : q0;
  if (hasOutside && (coneEmpty || q0 > ta) && ta <= p1) {
    if (terrainRayAltitude(r, mu, R, ta) <= outsideHeight)
      return terrainFinish(ta, 3, normalize(o + ta * d), outsideHeight);
    float near, far;
    if (raySphereRoots(r, mu, R + outsideHeight, near, far) && near >= ta && near <= p1)
      return terrainFinish(near, 3, normalize(o + near * d), outsideHeight);
  }
  if (coneEmpty) return terrainNoHit();

  // Over the grid: already under the field at its start?
  {
    vec2 plane = terrainPlaneAlongRay(o, d, q0, R);
    plane = clamp(plane, vec2(X0, Y0), vec2(X1, Y1));
    vec4 heights;
    vec2 fraction;
    float h = terrainSampleClamped(plane, heights, fraction);
    if (terrainRayAltitude(r, mu, R, q0) <= h) {
      if (q0 > ta && q0 == coneEnter && enterIndex >= 0 && enterIndex < 4)
        return terrainFinish(q0, 2, -normalize(constraints[enterIndex]), h);
      return terrainFinish(q0, 1, terrainFieldNormal(plane, R), h);
    }
  }

  int ncx = terrain.grid_size.x - 1, ncy = terrain.grid_size.y - 1;
  int topLevel = terrain.grid_size.z - 1;
  float dx = terrain.grid.z, dy = terrain.grid.w;
  float stepX = terrainPlaneStepX(o, d), stepY = terrainPlaneStepY(o, d);
  float t = q0;
  vec2 plane0 = terrainPlaneAlongRay(o, d, t, R);
  int ix = clamp(int(floor((plane0.x - X0) / dx)), 0, ncx - 1);
  int iy = clamp(int(floor((plane0.y - Y0) / dy)), 0, ncy - 1);
  int level = topLevel;
  int guard = min(8 * (ncx + ncy + 2) * (topLevel + 2) + 64, 1 << 20);
  for (int iteration = 0; iteration < guard; ++iteration) {
    int ni = ix >> level, nj = iy >> level;
    int i0 = ni << level, i1 = min((ni + 1) << level, ncx);
    int j0 = nj << level, j1 = min((nj + 1) << level, ncy);
    float tx = kTerrainInfinity, ty = kTerrainInfinity;
    if (stepX > 0.0) tx = terrainCrossingX(o, d, X0 + float(i1) * dx, R);
    if (stepX < 0.0) tx = terrainCrossingX(o, d, X0 + float(i0) * dx, R);
    if (stepY > 0.0) ty = terrainCrossingY(o, d, Y0 + float(j1) * dy, R);
    if (stepY < 0.0) ty = terrainCrossingY(o, d, Y0 + float(j0) * dy, R);
    tx = max(tx, t);
    ty = max(ty, t);
    float nodeExit = min(min(tx, ty), q1);
    vec2 range = terrainNodeRange(level, ni, nj);
    float lo, hi;
    bool reachesBottom;
    if (terrainCellSpan(ray, range.x, range.y, t, nodeExit, lo, hi, reachesBottom)) {
      if (level > 0) {
        // The child under the ray at lo, the leaf indices moving only in the ray's direction.
        t = lo;
        vec2 plane = terrainPlaneAlongRay(o, d, t, R);
        int jx = clamp(int(floor((plane.x - X0) / dx)), 0, ncx - 1);
        int jy = clamp(int(floor((plane.y - Y0) / dy)), 0, ncy - 1);
        if (stepX > 0.0) jx = max(jx, ix);
        if (stepX < 0.0) jx = min(jx, ix);
        if (stepY > 0.0) jy = max(jy, iy);
        if (stepY < 0.0) jy = min(jy, iy);
        ix = clamp(jx, i0, i1 - 1);
        iy = clamp(jy, j0, j1 - 1);
        --level;
        continue;
      }
      vec4 cell = vec4(X0 + float(ix) * dx, Y0 + float(iy) * dy, dx, dy);
      vec4 heights = terrainCellHeights(ix, iy);
      float tHit;
      bool hitCell = terrainCellHit(ray, cell, heights, lo, hi, 20, tHit);
      if (!hitCell && reachesBottom) {
        hitCell = true;
        tHit = hi;
      }
      if (hitCell) {
        vec2 plane = terrainPlaneAlongRay(o, d, tHit, R);
        vec2 fraction = clamp((plane - cell.xy) / cell.zw, 0.0, 1.0);
        float h = terrainBilinear(heights, fraction);
        vec2 gradient = terrainBilinearGradient(heights, fraction, cell.zw);
        return terrainFinish(tHit, 1, terrainSurfaceNormal(plane, h, gradient, R), h);
      }
    }
    if (nodeExit >= q1) break;
    t = nodeExit;
    if (tx <= ty) ix = stepX > 0.0 ? i1 : i0 - 1;
    if (ty <= tx) iy = stepY > 0.0 ? j1 : j0 - 1;
    if (ix < 0 || ix >= ncx || iy < 0 || iy >= ncy) break;
    level = min(level + 1, topLevel);
  }

  // Past the grid: the outside solid, its wall facing the grid where the ray leaves the cone.
  if (hasOutside && q1 < tb) {
    bool wall = exitIndex >= 0 && exitIndex < 4;
    if (terrainRayAltitude(r, mu, R, q1) <= outsideHeight)
      return terrainFinish(q1, wall ? 2 : 3, wall ? normalize(constraints[exitIndex]) : normalize(o + q1 * d),
                           outsideHeight);
    float near, far;
    if (raySphereRoots(r, mu, R + outsideHeight, near, far) && near >= q1 && near <= tb)
      return terrainFinish(near, 3, normalize(o + near * d), outsideHeight);
  }
  return terrainNoHit();
}

#endif  // FIRMAMENT_TERRAIN_CAST_GLSL
