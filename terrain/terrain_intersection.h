#pragma once
// A ray against a height field on the curved planet, on the CPU: the reference that the renderer's
// tests and the CPU reference renderer use, and the algorithm the GPU ray cast mirrors (its per-cell
// arithmetic is shaders/common/terrain_geometry.glsl, shared).
//
// The solid is every point at or below the surface: inside the grid's rectangle the bilinear field,
// outside it the sphere at the field's outsideHeight (none if NaN), with vertical walls between them
// (terrain/height_field.h). A hit is the first point of the ray at or inside the solid:
//   - the ray is first clipped to the sphere of the highest height (field or outside) and to the cone
//     of directions over the grid's rectangle (four planes through the planet centre, where the
//     gnomonic plane's grid lines lie, and z > 0), which splits it into at most three parts: outside
//     the grid, over it, outside again;
//   - outside, the sphere at outsideHeight is intersected in closed form (geometry.glsl's roots);
//   - over the grid, a quadtree walk of the min/max pyramid (Tevs et al. 2008): a node whose highest
//     height the ray stays above over the node's span is skipped whole (ray–sphere roots give where
//     the ray dips below that height), else the walk descends; a leaf cell is tested exactly
//     (terrainCellHit); after leaving a node the walk steps to its neighbour and goes up a level.
//     The ray's projection on the gnomonic plane is a straight line and each grid line is crossed
//     where the ray meets a plane, so the walk visits exactly the cells the ray passes over.
// A ray that starts inside the solid (under the terrain) hits at its start, with startedInside set.
#include <limits>

#include <glm/glm.hpp>

#include "terrain/height_field.h"
#include "terrain/min_max_pyramid.h"

namespace firmament::terrain {

struct TerrainRay {
  glm::dvec3 origin{0.0};               // planet-centred, ENU axes of the location (metres)
  glm::dvec3 direction{0.0, 0.0, 1.0};  // normalised by the intersector
  double tMin = 0.0;
  double tMax = std::numeric_limits<double>::infinity();
};

enum class TerrainSurface { None, Field, Wall, Outside };

struct TerrainHit {
  bool hit = false;
  double t = std::numeric_limits<double>::infinity();
  TerrainSurface surface = TerrainSurface::None;
  bool startedInside = false;  // the ray's start was already in the solid (t = tMin)
  glm::dvec3 position{0.0};    // planet-centred
  glm::dvec3 normal{0.0};      // unit, outward
  glm::dvec2 plane{0.0};       // gnomonic plane point under the hit
  double height = 0.0;         // the surface height there (m above the sphere)
  // Work done (the cost of the walk): pyramid nodes looked at, leaf cells tested exactly.
  int nodesVisited = 0;
  int cellsTested = 0;
};

class TerrainIntersector {
 public:
  // Builds the pyramid; the field must pass checkHeightField and stay alive as long as this object.
  TerrainIntersector(const HeightField& field, double planetRadius);

  const HeightField& field() const { return *field_; }
  const MinMaxPyramid& pyramid() const { return pyramid_; }
  double planetRadius() const { return planetRadius_; }

  // The first hit along the ray in [tMin, tMax], with the pyramid's empty-space skipping.
  TerrainHit intersect(const TerrainRay& ray) const;
  // The same walk over every leaf cell the ray passes over, no skipping: what the pyramid must agree
  // with, and its cost without it.
  TerrainHit intersectCellByCell(const TerrainRay& ray) const;

  // Bisection steps of the leaf test (30: 1e-9 of a cell's span).
  static constexpr int kRefinementSteps = 30;

 private:
  TerrainHit walk(const TerrainRay& ray, bool usePyramid) const;
  const HeightField* field_;
  MinMaxPyramid pyramid_;
  double planetRadius_;
};

}  // namespace firmament::terrain
