// terrain_geometry.glsl: a height field on the curved planet, the per-cell arithmetic of casting a ray
// at it. Shared with C++ (double) by the rules of compat.glsl: terrain/terrain_intersection.cpp walks
// the min/max pyramid on the CPU with these functions, and a GPU ray cast calls the same ones.
//
// Frame: planet-centred, metres, axes along the local East-North-Up directions of the scene's location
// (x east, y north, z up), as the renderer's (sky/scene_view.h). The planet is a sphere of radius R
// (the atmosphere's ground radius: sea level); heights are metres above it.
//
// The height field lies on the gnomonic (central) projection of that sphere onto the plane z = R
// tangent at the location: the plane point (x, y) is the direction normalize(x, y, R), and the surface
// point of height h there is P = (R + h) normalize(x, y, R) (Snyder 1987, "Map projections — a working
// manual", USGS Professional Paper 1395, §22). A gnomonic plane maps every great circle to a straight
// line, so the projection of a straight ray is a straight line and the ray crosses a grid line x = X
// exactly where it crosses the plane through the planet centre R p.x − X p.z = 0: a grid walk (DDA)
// over the plane is exact, as on a flat height field. The price is the projection's scale, 1/cos²θ
// radially and 1/cosθ across (θ the angle from the location): +0.025 % at 100 km, +0.22 % at 300 km.
//
// Float precision (the GPU): the ray is given as an origin and unit direction in this frame plus its
// start radius r and mu = cos(zenith) (geometry.glsl). The altitude along the ray is formed as
// (|p|² − R²) / (|p| + R) with |p|² − R² = (r − R)(r + R) + t (2 r mu + t), never as |p| − R, which in
// float loses ~0.5 m at the planet's radius. A renderer keeps the origin near the z axis (the camera is
// at x = y = 0), so the plane coordinates R p.x / p.z lose nothing to the planet's size either.
#ifndef FIRMAMENT_TERRAIN_GEOMETRY_GLSL
#define FIRMAMENT_TERRAIN_GEOMETRY_GLSL

#include "common/compat.glsl"
#include "common/geometry.glsl"

SHARED_BEGIN

// What a cell test returns when a crossing is parallel to the ray (never reached).
const Real kTerrainNever = 1.0e30;

// The gnomonic plane coordinates of the planet-centred point p (p.z > 0).
SHARED_INLINE vec2 terrainPlanePoint(vec3 p, Real planetRadius) {
  return vec2(planetRadius * p.x / p.z, planetRadius * p.y / p.z);
}

// The plane coordinates of the point at distance t along the ray origin + t direction.
SHARED_INLINE vec2 terrainPlaneAlongRay(vec3 origin, vec3 direction, Real t, Real planetRadius) {
  Real z = origin.z + t * direction.z;
  return vec2(planetRadius * (origin.x + t * direction.x) / z, planetRadius * (origin.y + t * direction.y) / z);
}

// The surface point of height h above the plane point (x, y): (R + h) normalize(x, y, R).
SHARED_INLINE vec3 terrainSurfacePoint(vec2 plane, Real height, Real planetRadius) {
  return (planetRadius + height) * normalize(vec3(plane.x, plane.y, planetRadius));
}

// The distance t at which the ray, moving along the plane's x axis in its direction of travel,
// crosses the grid line x = X of the plane (the plane through the planet centre R p.x − X p.z = 0);
// kTerrainNever when it never does. t = (X o.z − R o.x) / (R d.x − X d.z). The plane point of a rising
// ray does not run off to infinity: R p.x / p.z tends to R d.x / d.z, so a line beyond that asymptote
// is never reached, and the formula's t for it is negative. For a line ahead (or at the current point)
// the crossing lies ahead exactly when the denominator has the sign of the travel (terrainPlaneStepX,
// the sign of d.x o.z − o.x d.z); testing that sign, not t ≥ 0, keeps a line the ray is on (t rounded
// a hair negative) crossed. A walk that took such a t as "now" would step across cells without moving
// along the ray, and test far cells at the ray's start: the sky seen through a rising ray near an
// axis (d.y ~ 0) would be the terrain kilometres away (tests/terrain/test_terrain_intersection.cpp,
// RisingRayAlongAGridLineNeverReachesTheLinesBeyondItsAsymptote).
SHARED_INLINE Real terrainCrossingX(vec3 origin, vec3 direction, Real lineX, Real planetRadius) {
  Real denominator = planetRadius * direction.x - lineX * direction.z;
  Real travel = direction.x * origin.z - origin.x * direction.z;
  if (denominator == 0.0 || (denominator > 0.0) != (travel > 0.0)) return kTerrainNever;
  return (lineX * origin.z - planetRadius * origin.x) / denominator;
}

SHARED_INLINE Real terrainCrossingY(vec3 origin, vec3 direction, Real lineY, Real planetRadius) {
  Real denominator = planetRadius * direction.y - lineY * direction.z;
  Real travel = direction.y * origin.z - origin.y * direction.z;
  if (denominator == 0.0 || (denominator > 0.0) != (travel > 0.0)) return kTerrainNever;
  return (lineY * origin.z - planetRadius * origin.y) / denominator;
}

// The sign (−1, 0, +1) of the ray's motion along the plane's x axis: constant along the whole ray,
// since d/dt of R p.x / p.z has the sign of direction.x origin.z − origin.x direction.z.
SHARED_INLINE Real terrainPlaneStepX(vec3 origin, vec3 direction) {
  return sign(direction.x * origin.z - origin.x * direction.z);
}

SHARED_INLINE Real terrainPlaneStepY(vec3 origin, vec3 direction) {
  return sign(direction.y * origin.z - origin.y * direction.z);
}

// The altitude above the sphere of radius R of the point at distance t along a ray that starts at
// radius r with mu = cos(zenith), formed without cancellation (see the top of the file).
SHARED_INLINE Real terrainRayAltitude(Real r, Real mu, Real planetRadius, Real t) {
  Real excess = (r - planetRadius) * (r + planetRadius) + t * (2.0 * r * mu + t);  // |p|² − R²
  Real radius = sqrt(max(r * r + t * (2.0 * r * mu + t), 0.0));
  return excess / (radius + planetRadius);
}

// Bilinear interpolation in a cell with corner heights (h00, h10, h01, h11) = heights.x, .y, .z, .w
// (first index east, second north) at the fractions f = (fx, fy) in [0, 1]².
SHARED_INLINE Real terrainBilinear(vec4 heights, vec2 f) {
  Real south = heights.x + (heights.y - heights.x) * f.x;
  Real north = heights.z + (heights.w - heights.z) * f.x;
  return south + (north - south) * f.y;
}

// The gradient (dh/dx, dh/dy) of the bilinear cell in metres per plane metre; spacing = the cell's
// width and length on the plane.
SHARED_INLINE vec2 terrainBilinearGradient(vec4 heights, vec2 f, vec2 spacing) {
  Real dx = ((heights.y - heights.x) * (1.0 - f.y) + (heights.w - heights.z) * f.y) / spacing.x;
  Real dy = ((heights.z - heights.x) * (1.0 - f.x) + (heights.w - heights.y) * f.x) / spacing.y;
  return vec2(dx, dy);
}

// The unit outward normal of the surface P(x, y) = (R + h) normalize(x, y, R) at the plane point
// `plane`, height h and plane gradient g: the gradient of F(p) = |p| − R − h(R p.x / p.z, R p.y / p.z),
//   ∇F = p / |p| − (L / (R + h)) [g.x (1, 0, −x / R) + g.y (0, 1, −y / R)],   L = |(x, y, R)|.
// At the location (x = y = 0) this is normalize(−g.x, −g.y, 1), the flat-ground normal.
SHARED_INLINE vec3 terrainSurfaceNormal(vec2 plane, Real height, vec2 gradient, Real planetRadius) {
  vec3 radial = vec3(plane.x, plane.y, planetRadius);
  Real lengthL = length(radial);
  Real scale = lengthL / (planetRadius + height);
  vec3 tilt = vec3(gradient.x, gradient.y, -(gradient.x * plane.x + gradient.y * plane.y) / planetRadius);
  return normalize(radial / lengthL - scale * tilt);
}

// The cosine of the surface's slope: its normal against the local vertical at the plane point.
SHARED_INLINE Real terrainSlopeCosine(vec2 plane, vec3 normal, Real planetRadius) {
  return clamp(dot(normal, normalize(vec3(plane.x, plane.y, planetRadius))), -1.0, 1.0);
}

// A cell of the grid: its south-west corner and size on the plane, its corner heights, and the ray.
struct TerrainCellRay {
  vec3 origin;     // planet-centred, the frame above
  vec3 direction;  // unit
  Real r;          // |origin|
  Real mu;         // cos(zenith) of the direction at the origin
  Real planetRadius;
};

// The ray's altitude minus the cell's surface height at distance t: > 0 above, ≤ 0 on or under the
// surface. Plane fractions are clamped to the cell, so rounding at its edges reads the edge.
SHARED_INLINE Real terrainCellGap(TerrainCellRay ray, vec4 cell, vec4 heights, Real t) {
  vec2 plane = terrainPlaneAlongRay(ray.origin, ray.direction, t, ray.planetRadius);
  vec2 f = vec2(clamp((plane.x - cell.x) / cell.z, 0.0, 1.0), clamp((plane.y - cell.y) / cell.w, 0.0, 1.0));
  return terrainRayAltitude(ray.r, ray.mu, ray.planetRadius, t) - terrainBilinear(heights, f);
}

// The first distance in [tEnter, tExit] at which the ray meets the bilinear surface of the cell
// (cell = (x0, y0, width, length) on the plane): false if it stays above. tEnter, tExit bound the
// part of the ray over the cell (a caller clips them to where the ray is below the cell's highest
// corner).
//
// The gap g(t) (terrainCellGap) is smooth over one cell, and within it a quadratic to a relative
// error of the order of (cell size / R)²: the ray's altitude is a hyperbola of t with curvature
// 1 / R, the bilinear height a quadratic of the plane position, which moves with t projectively
// (relative non-linearity ~ cell / R). So: g at both ends and the middle; a sign change brackets the
// first root (a quadratic has at most two, so with g(tEnter) > 0 the first change is the first root);
// without one, the quadratic through the three values says where the gap has its minimum, and g
// there decides. The bracket is then halved `iterations` times (30 leaves 1e-9 of the
// cell's span in double; 20 reach float's resolution). A dip that the quadratic does not see is
// narrower than the cubic term: a graze by less than ~ h (cell / R)² (1e-8 m for a 10 m cell).
// The search above as a function body over any gap GAP(t) (GLSL has no function arguments): the LOD
// cast's terrainLodCellHit (terrain/terrain_cast.glsl) runs it on its blended surface. The enclosing
// function has the parameters tEnter, tExit, iterations and the out parameter tHit.
#define FIRMAMENT_TERRAIN_FIRST_ROOT(GAP)                          \
  tHit = tEnter;                                                   \
  Real g0 = GAP(tEnter);                                           \
  if (g0 <= 0.0) return true;                                      \
  if (!(tExit > tEnter)) return false;                             \
  Real tMiddle = 0.5 * (tEnter + tExit);                           \
  Real gMiddle = GAP(tMiddle);                                     \
  Real g1 = GAP(tExit);                                            \
  Real lo = tEnter;                                                \
  Real hi = tExit;                                                 \
  bool bracketed = false;                                          \
  if (gMiddle <= 0.0) {                                            \
    hi = tMiddle;                                                  \
    bracketed = true;                                              \
  } else if (g1 <= 0.0) {                                          \
    lo = tMiddle;                                                  \
    bracketed = true;                                              \
  } else {                                                         \
    /* g(s) = a s^2 + b s + g0 over s = (t - tEnter) / (tExit - tEnter) through the three values. */ \
    Real a = 2.0 * g1 + 2.0 * g0 - 4.0 * gMiddle;                  \
    Real b = g1 - g0 - a;                                          \
    if (a > 0.0) {                                                 \
      Real s = -b / (2.0 * a);                                     \
      if (s > 0.0 && s < 1.0) {                                    \
        Real tLow = tEnter + s * (tExit - tEnter);                 \
        if (GAP(tLow) <= 0.0) {                                    \
          hi = tLow;                                               \
          bracketed = true;                                        \
        }                                                          \
      }                                                            \
    }                                                              \
  }                                                                \
  if (!bracketed) return false;                                    \
  for (int i = 0; i < iterations; ++i) {                           \
    Real mid = 0.5 * (lo + hi);                                    \
    if (GAP(mid) <= 0.0) {                                         \
      hi = mid;                                                    \
    } else {                                                       \
      lo = mid;                                                    \
    }                                                              \
  }                                                                \
  tHit = hi;                                                       \
  return true;

SHARED_INLINE bool terrainCellHit(TerrainCellRay ray, vec4 cell, vec4 heights, Real tEnter, Real tExit,
                                  int iterations, OUT(Real) tHit) {
#define FIRMAMENT_TERRAIN_CELL_GAP(t) terrainCellGap(ray, cell, heights, t)
  FIRMAMENT_TERRAIN_FIRST_ROOT(FIRMAMENT_TERRAIN_CELL_GAP)
#undef FIRMAMENT_TERRAIN_CELL_GAP
}

// The part of [tEnter, tExit] (the ray over a cell or a node) where the ray can meet a surface whose
// heights lie in [hMin, hMax]: from where it dips below hMax to where it reaches hMin (ray–sphere roots
// of R + hMax and R + hMin, geometry.glsl). False if the ray stays above hMax over the span. When the
// span ends because the ray reaches hMin, reachesBottom is set: the ray is in the solid at tTo, so a
// cell test that finds no root before tTo (a root closer to tTo than rounding) hits at tTo. Clipping
// to hMin also keeps a steep ray's span, and so its bisection, as short as the cell's relief.
SHARED_INLINE bool terrainCellSpan(TerrainCellRay ray, Real hMin, Real hMax, Real tEnter, Real tExit, OUT(Real) tFrom,
                                   OUT(Real) tTo, OUT(bool) reachesBottom) {
  tFrom = tEnter;
  tTo = tExit;
  reachesBottom = false;
  Real near = 0.0;
  Real far = 0.0;
  if (!raySphereRoots(ray.r, ray.mu, ray.planetRadius + hMax, near, far) || far < tEnter) return false;
  tFrom = max(tEnter, near);
  tTo = min(tExit, far);
  if (tFrom > tTo) return false;
  if (raySphereRoots(ray.r, ray.mu, ray.planetRadius + hMin, near, far) && near >= tFrom && near <= tTo) {
    tTo = near;
    reachesBottom = true;
  }
  return true;
}

SHARED_END

#endif  // FIRMAMENT_TERRAIN_GEOMETRY_GLSL
