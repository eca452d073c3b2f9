#pragma once
// 8-bit PNG files (libpng): previews and error heat maps. Pixels are sRGB-encoded, row 0 at the top;
// the file carries an sRGB chunk and optional tEXt entries (e.g. the exposure a preview used).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace firmament {

struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 3;                         // 1 = grey, 2 = grey + alpha, 3 = RGB, 4 = RGBA
  std::vector<uint8_t> pixels;              // row-major, channels interleaved
  std::map<std::string, std::string> text;  // uncompressed tEXt entries
};

// Writes width × height pixels of `channels` (1..4) interleaved bytes atomically
// (core/atomic_file.h). A bad shape is a RuntimeError; a missing folder an InputError.
void writePng(const std::filesystem::path& path, int width, int height, int channels, const uint8_t* pixels,
              const std::map<std::string, std::string>& text = {});

// Reads any PNG as 8-bit grey/grey+alpha/RGB/RGBA (16-bit is reduced, palettes expanded). A missing,
// unreadable or non-PNG file is an InputError naming the file and the reason.
Image8 readPng(const std::filesystem::path& path);  // also returns the tEXt entries

// A grey PNG's samples as 16-bit integers, exactly as stored (no gamma or sRGB conversion: height maps
// are data, not pictures); an 8-bit file's samples come back in 0..255 with bitDepth 8.
struct Grey16 {
  int width = 0;
  int height = 0;
  int bitDepth = 16;              // of the file: 1, 2, 4, 8 or 16
  std::vector<uint16_t> samples;  // row-major, row 0 at the top
};

// A missing or non-PNG file, or a PNG that is not grey (colour, palette; grey + alpha is read without
// its alpha) is an InputError naming the file and what it holds.
Grey16 readPngGrey16(const std::filesystem::path& path);

// Writes 16-bit grey samples atomically, as stored (no sRGB chunk).
void writePngGrey16(const std::filesystem::path& path, int width, int height, const uint16_t* samples);

}  // namespace firmament
