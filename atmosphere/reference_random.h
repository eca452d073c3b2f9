#pragma once
// Random numbers for the reference path tracer: xoshiro256** (Blackman & Vigna 2018), seeded through
// SplitMix64 from (seed, stream). One stream per pixel (or per view direction), so a result depends
// on the seed and the pixel only, never on the thread that rendered it.
#include <cstdint>

namespace firmament::reference {

// SplitMix64 step (Steele, Lea & Flood 2014): a bijective mix, used to expand seeds.
inline uint64_t splitMix64(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class Random {
 public:
  Random(uint64_t seed, uint64_t stream) {
    uint64_t s = seed ^ (0xD1B54A32D192ED03ull * (stream + 1));
    // A second mix of the stream keeps neighbouring streams of neighbouring seeds apart.
    uint64_t t = splitMix64(s) ^ stream;
    for (auto& word : state_) word = splitMix64(t);
  }

  uint64_t nextBits() {
    const uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1): the top 53 bits.
  double uniform() { return double(nextBits() >> 11) * 0x1.0p-53; }

 private:
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t state_[4];
};

}  // namespace firmament::reference
