#pragma once
// sumField (weather_state.cpp) accumulated inside a loop that produces or reads the field four cells at a
// time, so that the sum costs no pass of its own over the field. The additions are sumField's, in its
// order (cell c goes into accumulator pair (c mod 8)/2, the cells past the last full block of eight into
// a running tail), so the total is the same double bit for bit.
#if defined(__SSE2__)
#include <emmintrin.h>

#include <cstddef>

namespace firmament::weather::sse {

class DomainSum {
 public:
  // For a field of n cells.
  explicit DomainSum(size_t n) : blocksEnd_(n - n % 8) {}
  // Adds cells c … c + 3 (c a multiple of 4; blocks in increasing order of c; a block left out adds 0).
  void add(size_t c, __m128 v) {
    if (c < blocksEnd_) {
      __m128d* pair = part_ + (c & 4 ? 2 : 0);
      pair[0] = _mm_add_pd(pair[0], _mm_cvtps_pd(v));
      pair[1] = _mm_add_pd(pair[1], _mm_cvtps_pd(_mm_movehl_ps(v, v)));
    } else {
      alignas(16) float x[4];
      _mm_store_ps(x, v);
      for (float value : x) tail_ += double(value);
    }
  }
  // Adds one cell past the last block of four (cells in increasing order).
  void addTail(float value) { tail_ += double(value); }
  // Σ, as sumField returns it once every cell was added.
  double total() const {
    alignas(16) double sum[2];
    _mm_store_pd(sum, _mm_add_pd(_mm_add_pd(part_[0], part_[1]), _mm_add_pd(part_[2], part_[3])));
    return (sum[0] + sum[1]) + tail_;
  }

 private:
  size_t blocksEnd_;
  __m128d part_[4] = {_mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd()};
  double tail_ = 0.0;
};

}  // namespace firmament::weather::sse
#endif
