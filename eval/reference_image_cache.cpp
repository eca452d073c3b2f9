#include "eval/reference_image_cache.h"

#include <cstdio>
#include <cstring>
#include <system_error>

#include "core/error.h"
#include "core/exr_io.h"
#include "core/hash.h"
#include "core/log.h"
#include "sky/scene_view.h"

namespace firmament {
namespace {

double metadataNumber(const Image& image, const std::string& key) {
  auto it = image.metadata.find(key);
  return it == image.metadata.end() ? 0.0 : std::strtod(it->second.c_str(), nullptr);
}

}  // namespace

std::string referenceCacheKey(const Scene& scene, const ReferenceQuality& q) {
  const std::string fields = std::to_string(q.samplesPerPixel) + "/" + std::to_string(q.wavelengthCount) + "/" +
                             std::to_string(q.seed) + "/" + roundTripDecimal(q.quadratureTolerance) + "/" +
                             roundTripDecimal(q.pathTolerance) + "/" + std::to_string(q.maxBounces) + "/" +
                             std::to_string(q.rouletteStartBounce) + "/" + std::to_string(q.forcedSegments) + "/" +
                             std::to_string(int(q.sunDisc)) + std::to_string(int(q.singleScattering)) +
                             std::to_string(int(q.multipleScattering)) + "/reference-v1";
  return scene.hash() + "-" + hex16(fnv1a(fields));
}

CachedReference cachedReferenceImage(const Scene& scene, const ReferenceQuality& quality,
                                     const std::filesystem::path& folder, const std::string& name) {
  CachedReference result;
  result.file = folder / (name + "-" + referenceCacheKey(scene, quality) + ".exr");
  const int width = int(scene.integer("/camera/width")), height = int(scene.integer("/camera/height"));
  std::error_code ec;
  if (std::filesystem::exists(result.file, ec)) {
    try {
      Image image = readExr(result.file);
      if (image.width == width && image.height == height && image.channels == 4) {
        result.image = std::move(image);
        result.fromCache = true;
        result.seconds = metadataNumber(result.image, "firmament.timing.reference_s");
        result.medianRelativeNoise = metadataNumber(result.image, "firmament.reference.noise_median_relative");
        result.p95RelativeNoise = metadataNumber(result.image, "firmament.reference.noise_p95_relative");
        return result;
      }
      logWarning("reference cache: " + result.file.string() + " has the wrong size; rendering it again");
    } catch (const std::exception& e) {
      logWarning(std::string("reference cache: ") + e.what() + "; rendering it again");
    }
  }

  const SceneView view = makeSceneView(scene);
  const ReferenceRenderer renderer(view.atmosphere, view.sunDirection, quality);
  ReferenceImage reference;
  {
    Progress progress("reference " + name, uint64_t(width) * uint64_t(height));
    reference = renderReferenceImage(renderer, view.cameraRadius, view.camera,
                                     [&](size_t done, size_t) { progress.set(done); });
  }
  Image image = std::move(reference.image);
  for (size_t i = 0; i < image.pixelCount(); ++i) image.pixels[i * 4 + 3] = float(reference.luminanceStandardError[i]);
  image.metadata["firmament.scene_hash"] = scene.hash();
  image.metadata["firmament.device"] = "cpu reference";
  image.metadata["firmament.units"] = "RGB: linear Rec.709, cd/m^2; A: standard error of the luminance, cd/m^2";
  image.metadata["firmament.reference.spp"] = std::to_string(quality.samplesPerPixel);
  image.metadata["firmament.reference.wavelengths"] = std::to_string(quality.wavelengthCount);
  image.metadata["firmament.reference.seed"] = std::to_string(quality.seed);
  image.metadata["firmament.reference.noise_median_relative"] = roundTripDecimal(reference.medianRelativeError);
  image.metadata["firmament.reference.noise_p95_relative"] = roundTripDecimal(reference.p95RelativeError);
  image.metadata["firmament.timing.reference_s"] = roundTripDecimal(reference.seconds);
  std::filesystem::create_directories(folder, ec);
  if (ec) throw InputError("cannot create " + folder.string() + ": " + ec.message());
  writeExr(result.file, image);
  result.image = std::move(image);
  result.seconds = reference.seconds;
  result.medianRelativeNoise = reference.medianRelativeError;
  result.p95RelativeNoise = reference.p95RelativeError;
  return result;
}

}  // namespace firmament
