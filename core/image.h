#pragma once
// An HDR image: linear, scene-referred Rec.709 RGB(A) floats in cd/m² (Y is luminance), row 0 at the
// top. Metadata travels with it into EXR headers and stats JSON.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace firmament {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 4;           // 3 = RGB, 4 = RGBA (A = coverage/transmittance where a pass writes one)
  std::vector<float> pixels;  // row-major, channels interleaved
  // String metadata: scene hash, device, per-pass timings, camera, sun direction (docs/formats.md).
  std::map<std::string, std::string> metadata;

  Image() = default;
  Image(int w, int h, int c = 4) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, 0.0f) {}
  float* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
  const float* at(int x, int y) const { return pixels.data() + (size_t(y) * width + x) * channels; }
  size_t pixelCount() const { return size_t(width) * size_t(height); }
};

}  // namespace firmament
