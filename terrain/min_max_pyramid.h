#pragma once
// The min/max pyramid of a height field, for empty-space skipping (Tevs, Ihrke & Seidel 2008, "Maximum
// mipmaps for fast, accurate, and scalable dynamic height field rendering", I3D; the minimum also lets
// a ray that is below a whole node stop at once).
//
// Level 0 has one texel per grid cell ((nx − 1) × (ny − 1)): the min and max of the cell's four
// corners, which bound its bilinear surface exactly. Level k + 1 halves each axis (rounding up): a
// texel holds the min and max of its (up to) 2 × 2 children, so a texel of level k bounds the
// 2^k × 2^k cells below it. The last level is a single texel: the field's range.
#include <vector>

#include "terrain/height_field.h"

namespace firmament::terrain {

struct MinMaxLevel {
  int width = 0;               // texels east
  int height = 0;              // texels north
  std::vector<float> minimum;  // width × height, row-major, row 0 south
  std::vector<float> maximum;
  float min(int i, int j) const { return minimum[size_t(j) * size_t(width) + size_t(i)]; }
  float max(int i, int j) const { return maximum[size_t(j) * size_t(width) + size_t(i)]; }
};

class MinMaxPyramid {
 public:
  MinMaxPyramid() = default;
  explicit MinMaxPyramid(const HeightField& field);

  int levels() const { return int(levels_.size()); }
  const MinMaxLevel& level(int k) const { return levels_[size_t(k)]; }
  float fieldMin() const { return levels_.back().minimum[0]; }
  float fieldMax() const { return levels_.back().maximum[0]; }

 private:
  std::vector<MinMaxLevel> levels_;
};

}  // namespace firmament::terrain
