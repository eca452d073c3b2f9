#pragma once
// Sparse iteration over the cells a column operator has work in. The per-cell physics of clouds, rain
// and storms touches a few percent of the domain; testing every cell with a branch mispredicts at every
// cloud edge and keeps the loop scalar. Instead an operator first decides, in a branch-free loop that
// vectorises, a byte per cell (1 = work), and then visits only those cells, in index order, skipping
// clear stretches eight cells at a time.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "weather/weather_state.h"

namespace firmament::weather {

using CellMask = std::vector<uint8_t>;  // 0 or 1 per cell

// What the column operators keep between their passes (held by the model, so a step allocates nothing).
struct ColumnScratch {
  CellMask active;
  std::vector<int32_t> index;
  Field value[3];
};

static_assert(std::endian::native == std::endian::little, "forEachActiveCell reads byte k of a word as cell k");

// Calls f(c) for every c with mask[c] != 0, in increasing order. Mask bytes must be 0 or 1 (one bit
// per byte, so clearing the lowest set bit of a word clears one cell).
template <class F>
void forEachActiveCell(const CellMask& mask, F&& f) {
  const uint8_t* m = mask.data();
  const size_t n = mask.size();
  size_t c = 0;
  for (; c + 8 <= n; c += 8) {
    uint64_t word;
    std::memcpy(&word, m + c, 8);
    while (word) {
      // Little-endian: byte k of the word is cell c + k.
      f(c + size_t(std::countr_zero(word) >> 3));
      word &= word - 1;
    }
  }
  for (; c < n; ++c)
    if (m[c]) f(c);
}

}  // namespace firmament::weather
