#include "clouds/noise_volume.h"

#include <cmath>

namespace firmament {
namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

}  // namespace

glm::dvec4 NoiseVolume::texel(int x, int y, int z) const {
  const size_t i =
      (size_t(wrap(z, depth)) * size_t(size) + size_t(wrap(y, size))) * size_t(size) + size_t(wrap(x, size));
  const float* t = texels.data() + 4 * i;
  return {t[0], t[1], t[2], t[3]};
}

glm::dvec4 NoiseVolume::sample(glm::dvec3 uvw) const {
  const glm::dvec3 x = uvw * double(size) - 0.5;
  const glm::dvec3 base = glm::floor(x);
  const glm::dvec3 f = x - base;
  const int x0 = int(std::fmod(base.x, double(size))), y0 = int(std::fmod(base.y, double(size))),
            z0 = int(std::fmod(base.z, double(size)));
  glm::dvec4 result(0.0);
  for (int corner = 0; corner < 8; ++corner) {
    const int cx = corner & 1, cy = (corner >> 1) & 1, cz = (corner >> 2) & 1;
    const double w = (cx ? f.x : 1.0 - f.x) * (cy ? f.y : 1.0 - f.y) * (cz ? f.z : 1.0 - f.z);
    result += w * texel(x0 + cx, y0 + cy, z0 + cz);
  }
  return result;
}

glm::dvec4 NoiseVolume::sample(glm::dvec2 uv) const {
  const glm::dvec2 x = uv * double(size) - 0.5;
  const glm::dvec2 base = glm::floor(x);
  const glm::dvec2 f = x - base;
  const int x0 = int(std::fmod(base.x, double(size))), y0 = int(std::fmod(base.y, double(size)));
  glm::dvec4 result(0.0);
  for (int corner = 0; corner < 4; ++corner) {
    const int cx = corner & 1, cy = (corner >> 1) & 1;
    const double w = (cx ? f.x : 1.0 - f.x) * (cy ? f.y : 1.0 - f.y);
    result += w * texel(x0 + cx, y0 + cy, 0);
  }
  return result;
}

}  // namespace firmament
