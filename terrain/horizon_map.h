#pragma once
// The terrain's horizon per texel and azimuth, from which the share of the sky a ground point sees
// follows (docs/terrain.md, "Sky light the terrain hides"; decision 0205).
//
// For every texel of a grid over the height field (the field's samples, or every stride-th of them) and
// each of A directions φ_k = 2π (k + ½) / A on the plane (east = 0, counter-clockwise), the elevation
// angle α_k of the highest terrain seen from the sample along φ_k: max over distances s of
// atan((h(s) − h₀ − s² / 2R) / s), s² / 2R the planet's curvature, h bilinear in the field, s from half a
// sample spacing to the grid's edge in geometric steps, then the outside sphere past the edge in closed
// form (its geometric horizon). The cosine-weighted share of the sky a surface of normal n sees above
// those horizons is the sum of terrainSkySlice (shaders/common/terrain_sky_visibility.glsl) over the
// azimuths, which the GPU cast (shaders/terrain/cast_terrain.comp) evaluates per pixel.
#include <vector>

#include "terrain/height_field.h"

namespace firmament::terrain {

struct HorizonMapSettings {
  int azimuths = 16;
  int maxTexels = 257;      // the grid's texels a side at most (every stride-th sample above it)
  double stepRatio = 1.12;  // each step's distance over the previous one
  int threads = 0;          // 0: all cores
};

struct HorizonMap {
  int width = 0, height = 0, azimuths = 0;
  int stride = 1;                // field samples per texel: texel (i, j) is sample (stride i, stride j)
  double x0 = 0.0, y0 = 0.0;     // plane position of texel (0, 0) (the field's sample (0, 0))
  double dx = 1.0, dy = 1.0;     // texel spacing (m)
  std::vector<float> elevation;  // ((j * width + i) * azimuths + k): horizon elevation (rad)
  double seconds = 0.0;          // the bake's time
  float at(int i, int j, int k) const {
    return elevation[(size_t(j) * size_t(width) + size_t(i)) * size_t(azimuths) + size_t(k)];
  }
};

// The horizon elevations of `field` on the planet of radius R (its sphere at sea level).
HorizonMap bakeHorizonMap(const HeightField& field, double planetRadius, const HorizonMapSettings& settings);

// The horizon's elevation (rad) from the plane point (x, y) inside the grid at height h0 along the
// plane direction (cos φ, sin φ), marched as bakeHorizonMap does.
double horizonElevation(const HeightField& field, double planetRadius, double x, double y, double h0, double phi,
                        double stepRatio);
// The same with the field's highest sample given (the march stops where nothing higher can be found).
double horizonElevation(const HeightField& field, double planetRadius, double x, double y, double h0, double phi,
                        double stepRatio, double fieldTop);

}  // namespace firmament::terrain
