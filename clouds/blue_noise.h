#pragma once
// A tileable 2D blue-noise threshold mask from a seed, for jittering march samples per pixel: the
// ranks of Ulichney's (1993) void-and-cluster method, in its simplest form (phase 3 from one seeded
// point): repeatedly put the next rank into the largest void, the pixel with the least energy of the
// toroidal Gaussian kernel (sigma 1.5 texels) around every pixel placed so far. Values are
// (rank + 0.5) / N², uniform in (0, 1), with the energy spectrum of blue noise (no low frequencies).
//
// Why on the CPU: the algorithm is sequential (N² dependent steps); for the 64² mask it takes a few
// milliseconds (energy updated incrementally, O(N⁴) additions), once per seed, and is cached with
// the GPU-baked textures.
#include <cstdint>
#include <vector>

namespace firmament {

std::vector<float> blueNoiseMask(int size, uint32_t seed);

}  // namespace firmament
