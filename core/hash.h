#pragma once
// FNV-1a (64 bit): a fast, stable hash for cache keys and scene identities (not cryptographic).
// Fowler, Noll and Vo; offset basis 14695981039346656037, prime 1099511628211.
#include <cstdint>
#include <string>
#include <string_view>

namespace firmament {

inline uint64_t fnv1a(std::string_view bytes, uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

// 16 lowercase hex digits.
std::string hex16(uint64_t value);

// A double as text that reads back as the same value (17 significant digits): a cache key's field.
std::string roundTripDecimal(double value);

}  // namespace firmament
