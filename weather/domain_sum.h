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
      const __m128d lo = _mm_cvtps_pd(v), hi = _mm_cvtps_pd(_mm_movehl_ps(v, v));
      if (c & 4) {
        part_[2] = _mm_add_pd(part_[2], lo);
        part_[3] = _mm_add_pd(part_[3], hi);
      } else {
        part_[0] = _mm_add_pd(part_[0], lo);
        part_[1] = _mm_add_pd(part_[1], hi);
      }
    } else {
      alignas(16) float x[4];
      _mm_store_ps(x, v);
      for (float value : x) tail_ += double(value);
    }
  }
  // Adds one cell past the last block of four (cells in increasing order).
  void addTail(float value) { tail_ += double(value); }
  // Adds cells begin … end − 1 of a field (begin a multiple of 4; ranges in increasing order; an end
  // that is not a multiple of 4 only at the field's end).
  void addRange(const float* field, size_t begin, size_t end) {
    size_t c = begin;
    if (c % 8 == 4 && c + 4 <= end) {
      add(c, _mm_loadu_ps(field + c));
      c += 4;
    }
    // Whole blocks of eight with the accumulators in registers.
    __m128d p0 = part_[0], p1 = part_[1], p2 = part_[2], p3 = part_[3];
    for (; c + 8 <= end && c + 8 <= blocksEnd_; c += 8) {
      const __m128 a = _mm_loadu_ps(field + c), b = _mm_loadu_ps(field + c + 4);
      p0 = _mm_add_pd(p0, _mm_cvtps_pd(a));
      p1 = _mm_add_pd(p1, _mm_cvtps_pd(_mm_movehl_ps(a, a)));
      p2 = _mm_add_pd(p2, _mm_cvtps_pd(b));
      p3 = _mm_add_pd(p3, _mm_cvtps_pd(_mm_movehl_ps(b, b)));
    }
    part_[0] = p0;
    part_[1] = p1;
    part_[2] = p2;
    part_[3] = p3;
    for (; c + 4 <= end; c += 4) add(c, _mm_loadu_ps(field + c));
    for (; c < end; ++c) addTail(field[c]);
  }
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
