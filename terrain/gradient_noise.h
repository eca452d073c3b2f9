#pragma once
// Seeded 2D gradient noise with its analytic derivative, deterministic across platforms: lattice
// gradients come from an integer hash of (cell, seed), and the arithmetic is IEEE double + − × only (no
// std::*_distribution, no transcendental functions, whose last bits differ between C libraries), so
// the same seed gives the same heights bit for bit on every machine with IEEE doubles and no fused
// multiply-add contraction (the project compiles as ISO C++, where GCC and Clang do not contract).
//
// Noise: Perlin 2002, "Improving noise" (ACM TOG 21(3)): gradients at the lattice corners, the quintic
// fade 6t⁵ − 15t⁴ + 10t³, here with 16 unit gradients at multiples of 22.5° for isotropy; derivative as
// in Quilez, "Gradient noise derivatives" (iquilezles.org, 2017). Hash: the SplitMix64 finaliser
// (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators", OOPSLA), whose
// avalanche passes the standard tests.
#include <cstdint>

namespace firmament::terrain {

struct NoiseSample {
  double value = 0.0;  // in [-1, 1] (scaled by √2 from the unit-gradient noise's ±√2/2)
  double dx = 0.0;     // d value / dx, per lattice unit
  double dy = 0.0;
};

// A 64-bit hash of a lattice point and a seed (SplitMix64 finaliser over their combination).
uint64_t latticeHash(int64_t i, int64_t j, uint64_t seed);

// Gradient noise at (x, y) in lattice units (one lattice cell = one wavelength).
NoiseSample gradientNoise(double x, double y, uint64_t seed);

}  // namespace firmament::terrain
