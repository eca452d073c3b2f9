#include "terrain/terrain_intersection.h"

#include <algorithm>
#include <cmath>

#include "common/geometry.glsl"
#include "common/terrain_geometry.glsl"

namespace firmament::terrain {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Constraint {
  glm::dvec3 gradient;  // f(p) = dot(gradient, p) ≥ 0 inside the cone
};

}  // namespace

TerrainIntersector::TerrainIntersector(const HeightField& field, double planetRadius)
    : field_(&field), pyramid_(field), planetRadius_(planetRadius) {}

TerrainHit TerrainIntersector::intersect(const TerrainRay& ray) const { return walk(ray, true); }
TerrainHit TerrainIntersector::intersectCellByCell(const TerrainRay& ray) const { return walk(ray, false); }

TerrainHit TerrainIntersector::walk(const TerrainRay& input, bool usePyramid) const {
  const HeightField& f = *field_;
  const double R = planetRadius_;
  const glm::dvec3 o = input.origin;
  const glm::dvec3 d = glm::normalize(input.direction);
  TerrainHit result;
  double r = 0.0, mu = 0.0;
  shared::rayRadiusAndCosine(o, d, r, mu);
  shared::TerrainCellRay cellRay;
  cellRay.origin = o;
  cellRay.direction = d;
  cellRay.r = r;
  cellRay.mu = mu;
  cellRay.planetRadius = R;
  auto altitude = [&](double t) { return shared::terrainRayAltitude(r, mu, R, t); };
  auto radialNormal = [&](double t) { return glm::normalize(o + t * d); };
  auto finish = [&](double t, TerrainSurface surface, const glm::dvec3& normal) {
    result.hit = true;
    result.t = t;
    result.surface = surface;
    result.position = o + t * d;
    result.normal = normal;
    result.startedInside = t <= input.tMin;
    if (result.position.z > 0.0) result.plane = shared::terrainPlanePoint(result.position, R);
    result.height = surface == TerrainSurface::Field ? f.sample(result.plane.x, result.plane.y) : altitude(t);
    if (surface == TerrainSurface::Outside) result.height = f.outsideHeight;
    return result;
  };

  // The sphere of the highest height bounds everything.
  const double fieldMax = pyramid_.fieldMax();
  const double top = f.hasOutside() ? std::max(fieldMax, f.outsideHeight) : fieldMax;
  double shellNear = 0.0, shellFar = 0.0;
  if (!shared::raySphereRoots(r, mu, R + top, shellNear, shellFar) || shellFar < input.tMin) {
    // Missed the bounding sphere: unless the ray starts inside the solid (only when it starts under
    // the top, i.e. r ≤ R + top, which a miss of the sphere excludes), no hit.
    return result;
  }
  const double ta = std::max(input.tMin, shellNear);
  const double tb = std::min(input.tMax, shellFar);
  if (!(ta <= tb)) return result;

  // The cone over the grid's rectangle: R p.x − X0 p.z ≥ 0, X1 p.z − R p.x ≥ 0, the same in y, p.z ≥ 0.
  const double X0 = f.x0, X1 = f.xMax(), Y0 = f.y0, Y1 = f.yMax();
  const Constraint constraints[5] = {
      {{R, 0.0, -X0}}, {{-R, 0.0, X1}}, {{0.0, R, -Y0}}, {{0.0, -R, Y1}}, {{0.0, 0.0, 1.0}}};
  double coneEnter = -kInfinity, coneExit = kInfinity;
  int enterIndex = -1, exitIndex = -1;
  bool coneEmpty = false;
  for (int k = 0; k < 5; ++k) {
    const double A = glm::dot(constraints[k].gradient, o), B = glm::dot(constraints[k].gradient, d);
    if (B == 0.0) {
      if (A < 0.0) coneEmpty = true;
    } else if (B > 0.0) {
      const double t = -A / B;
      if (t > coneEnter) {
        coneEnter = t;
        enterIndex = k;
      }
    } else {
      const double t = -A / B;
      if (t < coneExit) {
        coneExit = t;
        exitIndex = k;
      }
    }
  }
  const double q0 = std::max(ta, coneEnter), q1 = std::min(tb, coneExit);
  coneEmpty = coneEmpty || !(q0 <= q1);

  // The sphere at outsideHeight on [p0, p1]; `wall` is the normal of the wall at p0 if p0 is where the
  // ray leaves the grid's cone (it meets the outside solid's face there).
  auto outside = [&](double p0, double p1, const glm::dvec3* wall) -> bool {
    if (!f.hasOutside() || !(p0 <= p1)) return false;
    if (altitude(p0) <= f.outsideHeight) {
      finish(p0, wall ? TerrainSurface::Wall : TerrainSurface::Outside, wall ? *wall : radialNormal(p0));
      return true;
    }
    double near = 0.0, far = 0.0;
    if (shared::raySphereRoots(r, mu, R + f.outsideHeight, near, far) && near >= p0 && near <= p1) {
      finish(near, TerrainSurface::Outside, radialNormal(near));
      return true;
    }
    return false;
  };

  if (coneEmpty) {
    outside(ta, tb, nullptr);
    return result;
  }
  if (q0 > ta && outside(ta, q0, nullptr)) return result;

  // Over the grid. At its start: already under the field (a wall if the ray enters through a face of
  // the cone, else the ray starts inside the solid or touches the top).
  {
    const glm::dvec2 plane = shared::terrainPlaneAlongRay(o, d, q0, R);
    const double x = std::clamp(plane.x, X0, X1), y = std::clamp(plane.y, Y0, Y1);
    if (altitude(q0) <= f.sample(x, y)) {
      if (q0 > ta && q0 == coneEnter && enterIndex >= 0 && enterIndex < 4)
        return finish(q0, TerrainSurface::Wall, -glm::normalize(constraints[enterIndex].gradient));
      finish(q0, TerrainSurface::Field, f.normal(x, y, R));
      return result;
    }
  }

  const int ncx = f.nx - 1, ncy = f.ny - 1;
  const int topLevel = pyramid_.levels() - 1;
  const double stepX = shared::terrainPlaneStepX(o, d), stepY = shared::terrainPlaneStepY(o, d);
  auto leafAt = [&](double t, int& ix, int& iy) {
    const glm::dvec2 plane = shared::terrainPlaneAlongRay(o, d, t, R);
    ix = std::clamp(int(std::floor((plane.x - X0) / f.dx)), 0, ncx - 1);
    iy = std::clamp(int(std::floor((plane.y - Y0) / f.dy)), 0, ncy - 1);
  };
  double t = q0;
  int ix = 0, iy = 0;
  leafAt(t, ix, iy);
  int level = usePyramid ? topLevel : 0;
  const long guard = 8L * (long(ncx) + long(ncy) + 2L) * long(topLevel + 2) + 64L;
  bool overGrid = true;
  for (long iteration = 0; iteration < guard && overGrid; ++iteration) {
    ++result.nodesVisited;
    const int ni = ix >> level, nj = iy >> level;
    const int i0 = ni << level, i1 = std::min((ni + 1) << level, ncx);
    const int j0 = nj << level, j1 = std::min((nj + 1) << level, ncy);
    double tx = kInfinity, ty = kInfinity;
    if (stepX > 0.0) tx = shared::terrainCrossingX(o, d, X0 + i1 * f.dx, R);
    if (stepX < 0.0) tx = shared::terrainCrossingX(o, d, X0 + i0 * f.dx, R);
    if (stepY > 0.0) ty = shared::terrainCrossingY(o, d, Y0 + j1 * f.dy, R);
    if (stepY < 0.0) ty = shared::terrainCrossingY(o, d, Y0 + j0 * f.dy, R);
    tx = std::max(tx, t);
    ty = std::max(ty, t);
    const double nodeExit = std::min(std::min(tx, ty), q1);
    const double nodeMin = pyramid_.level(level).min(ni, nj), nodeMax = pyramid_.level(level).max(ni, nj);
    double lo = 0.0, hi = 0.0;
    bool reachesBottom = false;
    if (shared::terrainCellSpan(cellRay, nodeMin, nodeMax, t, nodeExit, lo, hi, reachesBottom)) {
      if (level > 0) {
        // The child under the ray at lo. The ray's leaf indices only move in its direction of travel,
        // so a position rounded back across a line already crossed keeps the index it had: without
        // this, a point on a child's far edge would send the walk back into that child for ever.
        t = lo;
        int jx = 0, jy = 0;
        leafAt(t, jx, jy);
        if (stepX > 0.0) jx = std::max(jx, ix);
        if (stepX < 0.0) jx = std::min(jx, ix);
        if (stepY > 0.0) jy = std::max(jy, iy);
        if (stepY < 0.0) jy = std::min(jy, iy);
        ix = std::clamp(jx, i0, i1 - 1);
        iy = std::clamp(jy, j0, j1 - 1);
        --level;
        continue;
      }
      ++result.cellsTested;
      const glm::dvec4 cell(X0 + ix * f.dx, Y0 + iy * f.dy, f.dx, f.dy);
      const glm::dvec4 heights(f.at(ix, iy), f.at(ix + 1, iy), f.at(ix, iy + 1), f.at(ix + 1, iy + 1));
      double tHit = 0.0;
      bool hitCell = shared::terrainCellHit(cellRay, cell, heights, lo, hi, kRefinementSteps, tHit);
      if (!hitCell && reachesBottom) {
        hitCell = true;
        tHit = hi;
      }
      if (hitCell) {
        const glm::dvec2 plane = shared::terrainPlaneAlongRay(o, d, tHit, R);
        const glm::dvec2 fraction(std::clamp((plane.x - cell.x) / f.dx, 0.0, 1.0),
                                  std::clamp((plane.y - cell.y) / f.dy, 0.0, 1.0));
        const double h = shared::terrainBilinear(heights, fraction);
        const glm::dvec2 gradient = shared::terrainBilinearGradient(heights, fraction, {f.dx, f.dy});
        finish(tHit, TerrainSurface::Field, shared::terrainSurfaceNormal(plane, h, gradient, R));
        result.height = h;
        return result;
      }
    }
    if (nodeExit >= q1) {
      overGrid = false;
      break;
    }
    t = nodeExit;
    if (tx <= ty) ix = stepX > 0.0 ? i1 : i0 - 1;
    if (ty <= tx) iy = stepY > 0.0 ? j1 : j0 - 1;
    if (ix < 0 || ix >= ncx || iy < 0 || iy >= ncy) {
      overGrid = false;
      break;
    }
    if (usePyramid) level = std::min(level + 1, topLevel);
  }

  // Past the grid: the outside solid, whose wall faces the grid where the ray leaves the cone.
  if (q1 < tb) {
    const glm::dvec3 wall =
        exitIndex >= 0 && exitIndex < 4 ? glm::normalize(constraints[exitIndex].gradient) : glm::dvec3(0.0, 0.0, 1.0);
    outside(q1, tb, exitIndex >= 0 && exitIndex < 4 ? &wall : nullptr);
  }
  return result;
}

}  // namespace firmament::terrain
