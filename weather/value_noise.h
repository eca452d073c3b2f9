#pragma once
// Deterministic, seedable, periodic value noise on the grid: the same seed gives the same field on
// every machine (integer hashing only; no std random engines, whose distributions vary by library).
#include <cstdint>
#include <vector>

namespace firmament::weather {

// 32-bit integer hash (Wang/Jenkins-style avalanche); public so tests and operators share it.
uint32_t hashCombine(uint32_t a, uint32_t b);
// Uniform in [0, 1) from a hash.
float unitFloat(uint32_t h);

// Smooth noise on an nx × ny periodic grid with feature size `period_cells` (rounded so that it tiles),
// a sum of `octaves` octaves, normalised to zero mean and unit standard deviation.
std::vector<float> periodicNoiseField(int nx, int ny, double period_cells, int octaves, uint32_t seed);

}  // namespace firmament::weather
