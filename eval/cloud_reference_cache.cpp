#include "eval/cloud_reference_cache.h"

#include <cstdlib>
#include <system_error>

#include "core/error.h"
#include "core/exr_io.h"
#include "core/hash.h"
#include "core/log.h"

namespace firmament {

std::string cloudReferenceCacheKey(const Scene& scene, const CloudReferenceSettings& s,
                                   const CloudNoiseSettings& noise) {
  const std::string fields = std::to_string(s.samplesPerPixel) + "/" + std::to_string(s.seed) + "/" +
                             std::to_string(s.maxEvents) + "/" + std::to_string(s.sunOpticalDepthSteps) + "/" +
                             roundTripDecimal(s.maxDistance_m) + "/" + std::to_string(s.maxScatteringOrder) + "/" +
                             roundTripDecimal(s.deltaLobeMinG) + "/" + std::to_string(int(s.exactSingleScattering)) +
                             "/noise " + std::to_string(noise.shapeSize) + " " + std::to_string(noise.detailSize) +
                             " " + std::to_string(noise.curlSize) + " " + std::to_string(noise.blueNoiseSize) +
                             "/cloud-reference-v" + std::to_string(kCloudReferenceVersion);
  return scene.hash() + "-" + hex16(fnv1a(fields));
}

CloudReferenceImage cachedCloudReference(const Scene& scene, const CloudPathTracer& tracer, glm::dvec3 cameraPosition,
                                         const shared::CameraParameters& camera, int threads,
                                         const CloudNoiseSettings& noise, const std::filesystem::path& folder,
                                         const std::string& name, bool* fromCache) {
  const CloudReferenceSettings& settings = tracer.settings();
  const std::string stem = name + "-" + cloudReferenceCacheKey(scene, settings, noise);
  const std::filesystem::path imageFile = folder / (stem + ".exr"), luminanceFile = folder / (stem + "-luminance.exr");
  const int width = camera.width, height = camera.height;
  if (fromCache) *fromCache = false;
  std::error_code ec;
  if (std::filesystem::exists(imageFile, ec) && std::filesystem::exists(luminanceFile, ec)) {
    try {
      CloudReferenceImage cached;
      cached.image = readExr(imageFile);
      const Image luminance = readExr(luminanceFile);
      const bool fits = cached.image.width == width && cached.image.height == height && cached.image.channels == 4 &&
                        luminance.width == width && luminance.height == height && luminance.channels == 4;
      if (fits) {
        const size_t n = cached.image.pixelCount();
        cached.luminance.resize(n);
        cached.luminanceStandardError.resize(n);
        const bool halves = settings.samplesPerPixel >= 2;
        if (halves) {
          cached.luminanceEvenPaths.resize(n);
          cached.luminanceOddPaths.resize(n);
        }
        cached.inAureole.assign(n, 0);
        for (size_t i = 0; i < n; ++i) {
          cached.luminance[i] = luminance.pixels[4 * i + 0];
          cached.luminanceStandardError[i] = luminance.pixels[4 * i + 1];
          if (halves) {
            cached.luminanceEvenPaths[i] = luminance.pixels[4 * i + 2];
            cached.luminanceOddPaths[i] = luminance.pixels[4 * i + 3];
          }
          // As renderCloudReference flags them: the pixel's ray inside the tracer's aureole cone.
          bool valid = true;
          const glm::dvec3 dir = shared::cameraRayDirection(
              camera, glm::dvec2(double(i % size_t(width)) + 0.5, double(i / size_t(width)) + 0.5), valid);
          cached.inAureole[i] = valid && glm::dot(dir, tracer.sunDirection()) > tracer.aureoleCosine() ? 1 : 0;
        }
        auto it = cached.image.metadata.find("firmament.timing.reference_s");
        if (it != cached.image.metadata.end()) cached.seconds = std::strtod(it->second.c_str(), nullptr);
        if (fromCache) *fromCache = true;
        return cached;
      }
      logWarning("cloud reference cache: " + imageFile.string() +
                 " does not fit the scene's image; rendering it again");
    } catch (const std::exception& e) {
      logWarning(std::string("cloud reference cache: ") + e.what() + "; rendering it again");
    }
  }
  CloudReferenceImage reference = renderCloudReference(tracer, cameraPosition, camera, threads);
  Image image = reference.image;
  image.metadata["firmament.scene_hash"] = scene.hash();
  image.metadata["firmament.device"] = "cpu cloud path tracer";
  image.metadata["firmament.units"] = "RGB: the clouds' light, linear Rec.709, cd/m^2; A: transmittance";
  image.metadata["firmament.reference.spp"] = std::to_string(settings.samplesPerPixel);
  image.metadata["firmament.reference.seed"] = std::to_string(settings.seed);
  image.metadata["firmament.timing.reference_s"] = roundTripDecimal(reference.seconds);
  Image luminance(image.width, image.height, 4);
  const bool halves = reference.luminanceOddPaths.size() == reference.luminance.size();
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    luminance.pixels[4 * i + 0] = float(reference.luminance[i]);
    luminance.pixels[4 * i + 1] = float(reference.luminanceStandardError[i]);
    luminance.pixels[4 * i + 2] = float(halves ? reference.luminanceEvenPaths[i] : reference.luminance[i]);
    luminance.pixels[4 * i + 3] = float(halves ? reference.luminanceOddPaths[i] : reference.luminance[i]);
  }
  luminance.metadata["firmament.units"] =
      "R: luminance, G: its standard error, B, A: the even and odd paths' luminance; cd/m^2";
  std::filesystem::create_directories(folder, ec);
  if (ec) throw InputError("cannot create " + folder.string() + ": " + ec.message());
  writeExr(luminanceFile, luminance);
  writeExr(imageFile, image);
  // What a later run reads back (float32): so that the first run's errors are the cached runs' to the
  // last digit.
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    reference.luminance[i] = luminance.pixels[4 * i + 0];
    reference.luminanceStandardError[i] = luminance.pixels[4 * i + 1];
    if (halves) {
      reference.luminanceEvenPaths[i] = luminance.pixels[4 * i + 2];
      reference.luminanceOddPaths[i] = luminance.pixels[4 * i + 3];
    }
  }
  return reference;
}

}  // namespace firmament
