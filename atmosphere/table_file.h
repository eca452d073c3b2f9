#pragma once
// Precomputed tables on disk: a small binary file per parameter hash, so a second run (or a
// time-lapse over one atmosphere) skips the precomputation. A file that is missing, truncated, of
// another version or for another key is ignored; writes go to a temporary file and are renamed.
//
// Layout (little-endian): "FMTABLE2", u32 key length, key bytes, u32 table count, then per table
// u32 width, height, depth, channels, u32 bytes per value (4: float32, 1: uint8, as the RGBA8 cloud
// noise) and width*height*depth*channels values.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace firmament {

struct TableData {
  uint32_t width = 0, height = 0, depth = 1, channels = 4;
  std::vector<float> values;   // float32 tables
  std::vector<uint8_t> bytes;  // uint8 tables (used when `values` is empty)
};

// The tables stored under `key`, or nothing when the file is absent or does not match.
std::optional<std::vector<TableData>> readTableFile(const std::filesystem::path& file, const std::string& key);

// Writes atomically; a failure is a warning (the cache is an optimisation), never an error.
void writeTableFile(const std::filesystem::path& file, const std::string& key, const std::vector<TableData>& tables);

}  // namespace firmament
