#include "terrain/gradient_noise.h"

#include <cmath>

namespace firmament::terrain {
namespace {

uint64_t splitMix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// cos and sin of k × 22.5°, k = 0..15, to the nearest double.
constexpr double kGradients[16][2] = {
    {1.0, 0.0},
    {0.92387953251128674, 0.38268343236508977},
    {0.70710678118654757, 0.70710678118654757},
    {0.38268343236508977, 0.92387953251128674},
    {0.0, 1.0},
    {-0.38268343236508977, 0.92387953251128674},
    {-0.70710678118654757, 0.70710678118654757},
    {-0.92387953251128674, 0.38268343236508977},
    {-1.0, 0.0},
    {-0.92387953251128674, -0.38268343236508977},
    {-0.70710678118654757, -0.70710678118654757},
    {-0.38268343236508977, -0.92387953251128674},
    {0.0, -1.0},
    {0.38268343236508977, -0.92387953251128674},
    {0.70710678118654757, -0.70710678118654757},
    {0.92387953251128674, -0.38268343236508977},
};

constexpr double kScale = 1.4142135623730951;  // √2: the noise's ±√2/2 to ±1

}  // namespace

uint64_t latticeHash(int64_t i, int64_t j, uint64_t seed) {
  return splitMix64(splitMix64(splitMix64(seed) ^ uint64_t(i)) ^ uint64_t(j));
}

NoiseSample gradientNoise(double x, double y, uint64_t seed) {
  const double fi = std::floor(x), fj = std::floor(y);  // floor is exact in IEEE arithmetic
  const int64_t i = int64_t(fi), j = int64_t(fj);
  const double u = x - fi, v = y - fj;
  const double* g00 = kGradients[latticeHash(i, j, seed) >> 60];
  const double* g10 = kGradients[latticeHash(i + 1, j, seed) >> 60];
  const double* g01 = kGradients[latticeHash(i, j + 1, seed) >> 60];
  const double* g11 = kGradients[latticeHash(i + 1, j + 1, seed) >> 60];
  const double n00 = g00[0] * u + g00[1] * v;
  const double n10 = g10[0] * (u - 1.0) + g10[1] * v;
  const double n01 = g01[0] * u + g01[1] * (v - 1.0);
  const double n11 = g11[0] * (u - 1.0) + g11[1] * (v - 1.0);
  const double fu = u * u * u * (u * (u * 6.0 - 15.0) + 10.0);
  const double fv = v * v * v * (v * (v * 6.0 - 15.0) + 10.0);
  const double du = 30.0 * u * u * (u * (u - 2.0) + 1.0);
  const double dv = 30.0 * v * v * (v * (v - 2.0) + 1.0);
  const double k1 = n10 - n00, k2 = n01 - n00, k3 = n00 - n10 - n01 + n11;
  NoiseSample s;
  s.value = kScale * (n00 + fu * k1 + fv * k2 + fu * fv * k3);
  const double gx =
      g00[0] + fu * (g10[0] - g00[0]) + fv * (g01[0] - g00[0]) + fu * fv * (g00[0] - g10[0] - g01[0] + g11[0]);
  const double gy =
      g00[1] + fu * (g10[1] - g00[1]) + fv * (g01[1] - g00[1]) + fu * fv * (g00[1] - g10[1] - g01[1] + g11[1]);
  s.dx = kScale * (gx + du * (k1 + fv * k3));
  s.dy = kScale * (gy + dv * (k2 + fu * k3));
  return s;
}

}  // namespace firmament::terrain
