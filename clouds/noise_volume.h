#pragma once
// A baked cloud noise texture on the CPU (read back from the GPU), sampled the way the GPU's linear,
// repeating sampler does: texel i holds the value at (i + 0.5) / size; a lookup at u finds
// x = u size - 0.5, blends texels floor(x) and floor(x) + 1 (both wrapped modulo size) with weight
// fract(x), per axis (trilinear in 3D, bilinear in 2D). The CPU path tracer reads the very texels the
// GPU march reads, so both see the same density field (docs/clouds.md, "Noise").
#include <glm/glm.hpp>
#include <vector>

namespace firmament {

struct NoiseVolume {
  int size = 0;               // texels per side
  int depth = 1;              // 1 for a 2D texture
  std::vector<float> texels;  // RGBA, x fastest, then y, then z

  glm::dvec4 texel(int x, int y, int z) const;
  glm::dvec4 sample(glm::dvec3 uvw) const;  // 3D, repeat
  glm::dvec4 sample(glm::dvec2 uv) const;   // 2D, repeat
};

}  // namespace firmament
