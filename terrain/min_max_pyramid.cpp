#include "terrain/min_max_pyramid.h"

#include <algorithm>

namespace firmament::terrain {

MinMaxPyramid::MinMaxPyramid(const HeightField& field) {
  checkHeightField(field);
  MinMaxLevel base;
  base.width = field.nx - 1;
  base.height = field.ny - 1;
  base.minimum.resize(size_t(base.width) * size_t(base.height));
  base.maximum.resize(base.minimum.size());
  for (int j = 0; j < base.height; ++j)
    for (int i = 0; i < base.width; ++i) {
      const float a = field.at(i, j), b = field.at(i + 1, j), c = field.at(i, j + 1), d = field.at(i + 1, j + 1);
      base.minimum[size_t(j) * size_t(base.width) + size_t(i)] = std::min(std::min(a, b), std::min(c, d));
      base.maximum[size_t(j) * size_t(base.width) + size_t(i)] = std::max(std::max(a, b), std::max(c, d));
    }
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const MinMaxLevel& child = levels_.back();
    MinMaxLevel parent;
    parent.width = (child.width + 1) / 2;
    parent.height = (child.height + 1) / 2;
    parent.minimum.resize(size_t(parent.width) * size_t(parent.height));
    parent.maximum.resize(parent.minimum.size());
    for (int j = 0; j < parent.height; ++j)
      for (int i = 0; i < parent.width; ++i) {
        float lo = child.min(2 * i, 2 * j), hi = child.max(2 * i, 2 * j);
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di) {
            const int ci = std::min(2 * i + di, child.width - 1), cj = std::min(2 * j + dj, child.height - 1);
            lo = std::min(lo, child.min(ci, cj));
            hi = std::max(hi, child.max(ci, cj));
          }
        parent.minimum[size_t(j) * size_t(parent.width) + size_t(i)] = lo;
        parent.maximum[size_t(j) * size_t(parent.width) + size_t(i)] = hi;
      }
    levels_.push_back(std::move(parent));
  }
}

}  // namespace firmament::terrain
