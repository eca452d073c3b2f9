// terrain_cast.glsl (GPU only): a ray against the height field on the curved planet, in float — the
// walk of terrain/terrain_intersection.cpp (TerrainIntersector::walk) line for line, with the same
// per-cell arithmetic (common/terrain_geometry.glsl, shared): the ray clipped to the sphere of the
// highest height and to the cone over the grid; outside it the sphere at the outside height in closed
// form; over the grid the min/max pyramid's quadtree walk (Tevs et al. 2008) down to the leaf cell's
// exact test (terrainCellHit, 20 halvings: float's resolution). The walk itself stays GLSL: its loop
// reads the pyramid through the buffers of terrain_block.glsl, which the CPU walk reads from its own
// classes (tests/sky/test_terrain_pass.cpp holds the two to the same hits).
//
// Level of detail (terrain/terrain_lod.h, docs/terrain.md "Level of detail"): terrainCastLod meets, at
// distance t, the field filtered to the footprint base + slope t (in field cells): the level
// lambda = log2(footprint), 0 (the field itself, the walk and arithmetic of terrainCast unchanged) where
// the footprint is under one cell, the blend (1 - f) h_k + f h_(k+1) of two levels' bilinear surfaces
// at lambda = k + f. The walk's bounds are the union of the bounds of the levels the node's span uses,
// so it skips no blended surface; a node inside one cell of every level the span uses is tested as a
// whole (terrainLodCellHit): far rays stop descending where the surface has no finer detail.
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

// The level of detail along a ray: the footprint in field cells at distance t is base + slope t.
struct TerrainLodRay {
  float base;
  float slope;
};

TerrainLodRay terrainLodNone() { return TerrainLodRay(0.0, 0.0); }

// The fractional LOD level at distance t: 0 while the footprint is under one cell, at most the highest.
float terrainLodLevel(TerrainLodRay lod, float t) {
  float footprint = lod.base + lod.slope * t;
  return footprint > 1.0 ? min(log2(footprint), terrain.lod.y) : 0.0;
}

// LOD level k's bilinear surface at a plane point clamped into its grid, and its plane gradient.
float terrainLodBilinear(int k, vec2 plane, out vec2 gradient) {
  vec4 heights;
  vec2 f;
  vec2 spacing = terrain.grid.zw;
  if (k == 0) {
    float h = terrainSampleClamped(plane, heights, f);
    gradient = terrainBilinearGradient(heights, f, spacing);
    return h;
  }
  ivec4 l = terrain.levels[k];
  spacing *= float(1 << k);
  vec2 g = (plane - terrain.grid.xy) / spacing;
  int i = clamp(int(floor(g.x)), 0, l.y - 1);
  int j = clamp(int(floor(g.y)), 0, l.z - 1);
  f = clamp(g - vec2(i, j), 0.0, 1.0);
  heights = vec4(terrainLodAt(k, i, j), terrainLodAt(k, i + 1, j), terrainLodAt(k, i, j + 1),
                 terrainLodAt(k, i + 1, j + 1));
  gradient = terrainBilinearGradient(heights, f, spacing);
  return terrainBilinear(heights, f);
}

// The surface at fractional level lambda: (1 - f) h_k + f h_(k+1), and its plane gradient.
float terrainLodHeight(vec2 plane, float lambda, out vec2 gradient) {
  int k = int(lambda);
  float f = lambda - float(k);
  float h = terrainLodBilinear(k, plane, gradient);
  if (f > 0.0) {
    vec2 g1;
    float h1 = terrainLodBilinear(k + 1, plane, g1);
    h = mix(h, h1, f);
    gradient = mix(gradient, g1, f);
  }
  return h;
}

// The smooth shading normal (terrainSmoothNormal) of LOD level k: its samples' central differences
// interpolated bilinearly; and its height there.
vec2 terrainLodVertexGradient(int k, int i, int j) {
  ivec4 l = terrain.levels[k];
  int nx = l.y + 1, ny = l.z + 1;
  int i0 = max(i - 1, 0), i1 = min(i + 1, nx - 1), j0 = max(j - 1, 0), j1 = min(j + 1, ny - 1);
  vec2 spacing = terrain.grid.zw * float(1 << k);
  return vec2((terrainLodAt(k, i1, j) - terrainLodAt(k, i0, j)) / (float(i1 - i0) * spacing.x),
              (terrainLodAt(k, i, j1) - terrainLodAt(k, i, j0)) / (float(j1 - j0) * spacing.y));
}

vec2 terrainLodSmoothGradient(int k, vec2 plane, out float height) {
  if (k == 0) {
    int ncx = terrain.grid_size.x - 1, ncy = terrain.grid_size.y - 1;
    vec2 g = (plane - terrain.grid.xy) / terrain.grid.zw;
    int i = clamp(int(floor(g.x)), 0, ncx - 1);
    int j = clamp(int(floor(g.y)), 0, ncy - 1);
    vec2 f = clamp(g - vec2(i, j), 0.0, 1.0);
    height = terrainBilinear(terrainCellHeights(i, j), f);
    return mix(mix(terrainVertexGradient(i, j), terrainVertexGradient(i + 1, j), f.x),
               mix(terrainVertexGradient(i, j + 1), terrainVertexGradient(i + 1, j + 1), f.x), f.y);
  }
  ivec4 l = terrain.levels[k];
  vec2 g = (plane - terrain.grid.xy) / (terrain.grid.zw * float(1 << k));
  int i = clamp(int(floor(g.x)), 0, l.y - 1);
  int j = clamp(int(floor(g.y)), 0, l.z - 1);
  vec2 f = clamp(g - vec2(i, j), 0.0, 1.0);
  height = terrainBilinear(vec4(terrainLodAt(k, i, j), terrainLodAt(k, i + 1, j), terrainLodAt(k, i, j + 1),
                                terrainLodAt(k, i + 1, j + 1)),
                           f);
  return mix(mix(terrainLodVertexGradient(k, i, j), terrainLodVertexGradient(k, i + 1, j), f.x),
             mix(terrainLodVertexGradient(k, i, j + 1), terrainLodVertexGradient(k, i + 1, j + 1), f.x), f.y);
}

// The shading normal at level lambda: the two levels' smooth gradients and heights blended (averaged
// heights, so the normals of a far slope are its filtered slope's); terrainSmoothNormal at lambda 0.
vec3 terrainLodSmoothNormal(vec2 plane, float lambda, float R) {
  if (lambda <= 0.0) return terrainSmoothNormal(plane, R);
  int k = int(lambda);
  float f = lambda - float(k);
  float h;
  vec2 gradient = terrainLodSmoothGradient(k, plane, h);
  if (f > 0.0) {
    float h1;
    vec2 g1 = terrainLodSmoothGradient(k + 1, plane, h1);
    h = mix(h, h1, f);
    gradient = mix(gradient, g1, f);
  }
  return terrainSurfaceNormal(plane, h, gradient, R);
}

// The ray's altitude minus the LOD surface at distance t, the plane point clamped into `node` (x0, y0,
// width, length): terrainCellGap for a node of any level and the blended surface.
float terrainLodGap(TerrainCellRay ray, TerrainLodRay lod, vec4 node, float t) {
  vec2 plane = clamp(terrainPlaneAlongRay(ray.origin, ray.direction, t, ray.planetRadius), node.xy, node.xy + node.zw);
  vec2 gradient;
  return terrainRayAltitude(ray.r, ray.mu, ray.planetRadius, t) -
         terrainLodHeight(plane, terrainLodLevel(lod, t), gradient);
}

// terrainCellHit (common/terrain_geometry.glsl) on the LOD surface over a node that lies in one cell of
// every level its span uses: the gap is smooth there (two bilinear patches blended by a smooth weight),
// so the same three samples, the quadratic's minimum and the halvings apply.
bool terrainLodCellHit(TerrainCellRay ray, TerrainLodRay lod, vec4 node, float tEnter, float tExit, int iterations,
                       out float tHit) {
#define FIRMAMENT_TERRAIN_LOD_GAP(t) terrainLodGap(ray, lod, node, t)
  FIRMAMENT_TERRAIN_FIRST_ROOT(FIRMAMENT_TERRAIN_LOD_GAP)
#undef FIRMAMENT_TERRAIN_LOD_GAP
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

// The first hit in [tMin, tMax] of the ray o + t d (d unit) with radius r and cosine mu at o, on the
// surface of the level of detail `lod` (terrainLodNone(): the field itself). terrainCastLod calls it.
TerrainCastHit terrainCastWalk(vec3 o, vec3 d, float r, float mu, float tMin, float tMax, TerrainLodRay lod) {
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
    float lambda0 = terrainLodLevel(lod, q0);
    vec2 gradient0;
    if (lambda0 > 0.0) h = terrainLodHeight(plane, lambda0, gradient0);
    if (terrainRayAltitude(r, mu, R, q0) <= h) {
      if (q0 > ta && q0 == coneEnter && enterIndex >= 0 && enterIndex < 4)
        return terrainFinish(q0, 2, -normalize(constraints[enterIndex]), h);
      if (lambda0 > 0.0) return terrainFinish(q0, 1, terrainSurfaceNormal(plane, h, gradient0, R), h);
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
    // The levels of detail over the node's span, and the bounds of every level they blend.
    float lambdaA = terrainLodLevel(lod, t), lambdaB = terrainLodLevel(lod, nodeExit);
    vec2 range;
    bool lodLeaf = false;
    if (lambdaB <= 0.0) {
      range = terrainNodeRange(level, ni, nj);
    } else {
      int kLo = int(lambdaA), kHi = min(int(lambdaB) + 1, int(terrain.lod.y));
      range = terrainLodNodeRange(kLo, level, ni, nj);
      for (int k = kLo + 1; k <= kHi; ++k) {
        vec2 bounds = terrainLodNodeRange(k, level, ni, nj);
        range = vec2(min(range.x, bounds.x), max(range.y, bounds.y));
      }
      // A node inside one cell of every level the span uses is tested whole.
      lodLeaf = level == 0 || (lambdaA >= 1.0 && level <= kLo);
    }
    float lo, hi;
    bool reachesBottom;
    if (terrainCellSpan(ray, range.x, range.y, t, nodeExit, lo, hi, reachesBottom)) {
      if (lodLeaf) {
        vec4 node = vec4(X0 + float(i0) * dx, Y0 + float(j0) * dy, float(i1 - i0) * dx, float(j1 - j0) * dy);
        float tHit;
        bool hitNode = terrainLodCellHit(ray, lod, node, lo, hi, 20, tHit);
        if (!hitNode && reachesBottom) {
          hitNode = true;
          tHit = hi;
        }
        if (hitNode) {
          vec2 plane = clamp(terrainPlaneAlongRay(o, d, tHit, R), node.xy, node.xy + node.zw);
          vec2 gradient;
          float h = terrainLodHeight(plane, terrainLodLevel(lod, tHit), gradient);
          return terrainFinish(tHit, 1, terrainSurfaceNormal(plane, h, gradient, R), h);
        }
      } else if (level > 0) {
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
      } else {
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

TerrainCastHit terrainCast(vec3 o, vec3 d, float r, float mu, float tMin, float tMax) {
  return terrainCastWalk(o, d, r, mu, tMin, tMax, terrainLodNone());
}

// The same on the surface of the level of detail `lod`: the field's own walk up to where the footprint
// passes one cell (there the surface is the field), the LOD walk beyond. Two walks, not one: the walk
// that carries the levels costs ~4x on lavapipe even where every level is 0 (its loop's larger state),
// so the near part keeps the lean one.
TerrainCastHit terrainCastLod(vec3 o, vec3 d, float r, float mu, float tMin, float tMax, TerrainLodRay lod) {
  float tLod = lod.slope > 0.0 ? (1.0 - lod.base) / lod.slope : (lod.base > 1.0 ? -kTerrainInfinity : kTerrainInfinity);
  if (tLod > tMin) {
    TerrainCastHit near = terrainCast(o, d, r, mu, tMin, min(tMax, tLod));
    if (near.hit || tLod >= tMax) return near;
    tMin = tLod;
  }
  return terrainCastWalk(o, d, r, mu, tMin, tMax, lod);
}

#endif  // FIRMAMENT_TERRAIN_CAST_GLSL
