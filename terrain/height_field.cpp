#include "terrain/height_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/terrain_geometry.glsl"

namespace firmament::terrain {
namespace {

// The cell holding x (clamped to the grid) and the fraction within it.
void locate(double x, double origin, double spacing, int samples, int& cell, double& fraction) {
  double u = (x - origin) / spacing;
  int c = int(std::floor(u));
  c = std::clamp(c, 0, samples - 2);
  cell = c;
  fraction = std::clamp(u - c, 0.0, 1.0);
}

glm::dvec4 corners(const HeightField& f, int i, int j) {
  return {f.at(i, j), f.at(i + 1, j), f.at(i, j + 1), f.at(i + 1, j + 1)};
}

}  // namespace

double HeightField::sample(double x, double y) const {
  if (!contains(x, y)) return outsideHeight;
  int i, j;
  double fx, fy;
  locate(x, x0, dx, nx, i, fx);
  locate(y, y0, dy, ny, j, fy);
  return shared::terrainBilinear(corners(*this, i, j), {fx, fy});
}

glm::dvec2 HeightField::gradient(double x, double y) const {
  if (!contains(x, y)) return {0.0, 0.0};
  int i, j;
  double fx, fy;
  locate(x, x0, dx, nx, i, fx);
  locate(y, y0, dy, ny, j, fy);
  return shared::terrainBilinearGradient(corners(*this, i, j), {fx, fy}, {dx, dy});
}

glm::dvec3 HeightField::normal(double x, double y, double planetRadius) const {
  const double h = contains(x, y) ? sample(x, y) : (hasOutside() ? outsideHeight : 0.0);
  return shared::terrainSurfaceNormal({x, y}, h, gradient(x, y), planetRadius);
}

double HeightField::minHeight() const {
  if (heights.empty()) return std::nan("");
  return *std::min_element(heights.begin(), heights.end());
}

double HeightField::maxHeight() const {
  if (heights.empty()) return std::nan("");
  return *std::max_element(heights.begin(), heights.end());
}

void checkHeightField(const HeightField& f) {
  if (f.nx < 2 || f.ny < 2 || !(f.dx > 0.0) || !(f.dy > 0.0) || f.heights.size() != size_t(f.nx) * size_t(f.ny))
    throw std::logic_error("height field of " + std::to_string(f.nx) + "x" + std::to_string(f.ny) + " samples, " +
                           std::to_string(f.heights.size()) + " heights, spacing " + std::to_string(f.dx) + " x " +
                           std::to_string(f.dy));
  for (float h : f.heights)
    if (!std::isfinite(h)) throw std::logic_error("height field with a non-finite height");
}

}  // namespace firmament::terrain
