#pragma once
// Cloud path-traced references kept on disk, keyed by the scene, the path tracer's settings and the
// noise texels, so a benchmark re-run (a model change judged against 1024-path references) pays only
// for the fast path. Two EXRs per key, float32 and lossless: <name>-<key>.exr is the reference image
// (RGB the clouds' light in cd/m^2, A the transmittance) and <name>-<key>-luminance.exr holds per pixel
// R the luminance, G its standard error, B and A the even and odd paths' luminance.
#include <filesystem>
#include <string>

#include "clouds/cloud_noise.h"
#include "clouds/reference_clouds.h"
#include "core/scene.h"

namespace firmament {

// Bumped whenever the cloud path tracer's output changes for the same settings (its transport, its
// random streams): cached references made before are then not reused.
constexpr int kCloudReferenceVersion = 1;

// "<scene hash>-<settings hash>": every field of CloudReferenceSettings that changes the pixels (not the
// thread count), the noise sizes and kCloudReferenceVersion.
std::string cloudReferenceCacheKey(const Scene& scene, const CloudReferenceSettings& settings,
                                   const CloudNoiseSettings& noise);

// Reads folder/<name>-<key>{,-luminance}.exr when both are present and fit the camera's image size;
// else renders the reference (renderCloudReference with these arguments) and writes it there
// (atomically, each file). The aureole flags are recomputed from the camera and the tracer either way;
// the halves are left empty for a reference of fewer than 2 paths per pixel. fromCache says which.
CloudReferenceImage cachedCloudReference(const Scene& scene, const CloudPathTracer& tracer, glm::dvec3 cameraPosition,
                                         const shared::CameraParameters& camera, int threads,
                                         const CloudNoiseSettings& noise, const std::filesystem::path& folder,
                                         const std::string& name, bool* fromCache = nullptr);

}  // namespace firmament
