#pragma once
// A height field: heights in metres above the planet's sphere (sea level) on a regular grid of the
// gnomonic plane tangent at the scene's location (shaders/common/terrain_geometry.glsl says why that
// plane), with bilinear sampling, its gradient, the surface normal, and a stated surface outside.
//
// Grid: nx × ny samples; sample (i, j) sits at the plane point (x0 + i dx, y0 + j dy), i eastwards,
// j northwards (row 0 is the southern edge; images are flipped when read or written, as their row 0
// is the north). The surface between samples is the bilinear interpolation of the four corners of the
// cell, so it is continuous, and a cell's heights are bounded by its corners (the min/max pyramid
// relies on it). Outside the grid's rectangle [x0, x0 + (nx − 1) dx] × [y0, y0 + (ny − 1) dy] the
// surface is the sphere at `outsideHeight` (NaN: no surface there; rays that leave the grid miss),
// joined to the grid's edge by a vertical wall where the two differ.
//
// Bilinear is the interpolation of record: it is the cheapest continuous one, it never overshoots its
// corners (bicubic does, which breaks the min/max bound), and it is what a GPU's linear filter does.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace firmament::terrain {

struct HeightField {
  int nx = 0;
  int ny = 0;
  double x0 = 0.0;             // plane position of sample (0, 0), metres east of the location
  double y0 = 0.0;             // metres north
  double dx = 1.0;             // sample spacing east, metres (> 0)
  double dy = 1.0;             // sample spacing north, metres (> 0)
  std::vector<float> heights;  // nx × ny, j-major: heights[j * nx + i]
  double outsideHeight = std::numeric_limits<double>::quiet_NaN();
  std::string source;  // where the heights came from (for reports)

  HeightField() = default;
  HeightField(int nx_, int ny_, double x0_, double y0_, double dx_, double dy_)
      : nx(nx_), ny(ny_), x0(x0_), y0(y0_), dx(dx_), dy(dy_), heights(size_t(nx_) * size_t(ny_), 0.0f) {}

  float& at(int i, int j) { return heights[size_t(j) * size_t(nx) + size_t(i)]; }
  float at(int i, int j) const { return heights[size_t(j) * size_t(nx) + size_t(i)]; }
  double xAt(int i) const { return x0 + i * dx; }
  double yAt(int j) const { return y0 + j * dy; }
  double xMax() const { return x0 + (nx - 1) * dx; }
  double yMax() const { return y0 + (ny - 1) * dy; }
  bool contains(double x, double y) const { return x >= x0 && x <= xMax() && y >= y0 && y <= yMax(); }
  bool hasOutside() const { return outsideHeight == outsideHeight; }

  // The surface height at a plane point: bilinear inside, outsideHeight outside.
  double sample(double x, double y) const;
  // (dh/dx, dh/dy) of the bilinear surface (metres per plane metre); zero outside.
  glm::dvec2 gradient(double x, double y) const;
  // The unit surface normal in the planet-centred frame of shaders/common/terrain_geometry.glsl.
  glm::dvec3 normal(double x, double y, double planetRadius) const;

  // The lowest and highest sample (the surface's own bounds); NaN for an empty field.
  double minHeight() const;
  double maxHeight() const;
};

// Throws std::logic_error when the field's shape is inconsistent (a caller's bug): nx, ny ≥ 2, spacings
// > 0, heights.size() == nx × ny, every height finite.
void checkHeightField(const HeightField& field);

}  // namespace firmament::terrain
