#pragma once
// OpenEXR files for HDR images (docs/formats.md, "EXR"). Writing: 32-bit float R,G,B[,A], scanline,
// ZIP (default) or PIZ compression — both lossless, so a round trip is bit-exact — plus every
// Image::metadata entry as a string attribute. Reading: any scanline or tiled file with R,G,B (A
// optional) in half, float or uint; string attributes come back as metadata.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/image.h"

namespace firmament {

enum class ExrCompression { Zip, Piz };

// Writes atomically (core/atomic_file.h). A metadata key that OpenEXR reserves ("channels",
// "compression", ...) or an image whose size does not match its pixels is a RuntimeError (a bug in
// the caller); a missing folder is an InputError.
void writeExr(const std::filesystem::path& path, const Image& image, ExrCompression compression = ExrCompression::Zip);

// A missing, unreadable, truncated or non-EXR file, or one without R,G,B channels, is an InputError
// that names the file and the reason. The image is the file's data window; A is read when present
// (channels = 4), else channels = 3.
Image readExr(const std::filesystem::path& path);

// One channel of data (heights, depths) as 32-bit floats, row 0 at the top.
struct ExrChannel {
  int width = 0;
  int height = 0;
  std::string name;
  std::vector<float> values;                    // row-major
  std::map<std::string, std::string> metadata;  // the file's string attributes
};

// Reads the first of `names` that the file has, or its only channel if it has one; errors as readExr,
// and an InputError naming the channels found when none fits.
ExrChannel readExrChannel(const std::filesystem::path& path, const std::vector<std::string>& names);

// Writes one FLOAT channel `name` (ZIP, lossless) with string attributes, atomically.
void writeExrChannel(const std::filesystem::path& path, const ExrChannel& channel);

}  // namespace firmament
