#pragma once
// CPU reference images kept on disk, keyed by the scene's hash and the reference's quality, so a
// benchmark re-run does not pay for them again. One EXR per key: RGB is the reference (linear
// Rec.709, cd/m²) and A the Monte Carlo standard error of each pixel's luminance (cd/m²); the
// header holds the quality, the noise statistics and the render time.
#include <filesystem>
#include <string>

#include "atmosphere/reference_renderer.h"
#include "core/image.h"
#include "core/scene.h"

namespace firmament {

struct CachedReference {
  Image image;  // RGBA, A = standard error of the luminance (cd/m²)
  std::filesystem::path file;
  bool fromCache = false;
  double seconds = 0.0;  // render wall clock (as recorded when it was rendered)
  double medianRelativeNoise = 0.0, p95RelativeNoise = 0.0;
};

// "<scene hash>-<quality hash>": every field of ReferenceQuality that changes the pixels (not the
// thread count).
std::string referenceCacheKey(const Scene& scene, const ReferenceQuality& quality);

// Reads folder/<name>-<key>.exr when present and valid, else renders the scene's clear sky with
// the CPU reference (progress bar labelled `name`) and writes it there atomically.
CachedReference cachedReferenceImage(const Scene& scene, const ReferenceQuality& quality,
                                     const std::filesystem::path& folder, const std::string& name);

}  // namespace firmament
