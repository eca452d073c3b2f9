#pragma once
// Level of detail by distance for the height field (docs/terrain.md, "Level of detail"; decision 0206):
// filtered copies of the field on coarser grids, and the min/max bounds of each, so that a ray cast can
// meet, far from the camera, the surface filtered to the pixel's footprint instead of point-sampling
// detail finer than a pixel (what makes far ridges alias and swim in a moving sequence).
//
// LOD level 0 is the field itself. Level k ≥ 1 has samples at the plane points (x0 + i 2^k dx,
// y0 + j 2^k dy), i = 0 … ceil((nx − 1) / 2^k) (the last may lie past the field's edge: its filter
// clamps to the edge), each the [1 2 1] / 4 tent of level k − 1 around it in x and y (indices clamped
// to the level): a vertex-centred mip, so a level-k cell is exactly 2^k × 2^k cells of the field and
// the min/max pyramid's level-k node over them. The surface at a fractional level λ = k + f is
// (1 − f) h_k + f h_{k+1}, each h_k bilinear in its own cells: continuous in position and in λ.
//
// Bounds: level k's surface over a pyramid node of level L ≥ k lies within the min and max of its
// samples at the corners of the level-k cells in the node (bilinear never overshoots its corners):
// `levelBounds[k]` is that min/max pyramid, its level 0 the level-k cells (= the pyramid's level k), so
// `levelBounds[0]` is the field's own MinMaxPyramid. The blend of levels k and k + 1 lies within the
// union of their bounds: a walk that takes the union over the levels a ray's span uses skips only
// space that no blended surface reaches.
#include <vector>

#include "terrain/height_field.h"
#include "terrain/min_max_pyramid.h"

namespace firmament::terrain {

struct TerrainLod {
  // levels[k]: the level-k field (levels[0] is a copy of the field's shape and heights); at most
  // maxLevel + 1 levels, and never past the pyramid's single top node.
  std::vector<HeightField> levels;
  std::vector<MinMaxPyramid> levelBounds;  // levelBounds[k] of levels[k]
};

// The levels 0 … min(maxLevel, the pyramid's top level) of `field` and their bounds.
TerrainLod buildTerrainLod(const HeightField& field, int maxLevel);

// The surface at plane point (x, y) and fractional level `lambda` (clamped to the levels built), for
// tests and the CPU side: (1 − f) h_k + f h_{k+1}, bilinear in each level's cells (clamped to its grid).
double sampleTerrainLod(const TerrainLod& lod, double x, double y, double lambda);

}  // namespace firmament::terrain
