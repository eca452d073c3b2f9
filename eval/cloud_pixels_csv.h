#pragma once
// A cloud image's pixels beside the path tracer's, one CSV row per pixel: where a model's error lies
// (which pixels, which scattering angles), for `bench clouds --images` and `--calibrate --images`.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "clouds/reference_clouds.h"
#include "core/image.h"
#include "sky/scene_view.h"

namespace firmament {

// Per pixel: x, y, the angle between its view ray and the direction to the sun (deg; 0 looking into
// the sun: forward scattering), the reference's luminance, standard error and transmittance (and the
// even and odd paths' luminance where the reference keeps them), then one column per entry of
// `columns` (name, luminance per pixel; commas in a name become ';'). Written atomically.
void writeCloudPixelsCsv(const std::filesystem::path& file, const SceneView& view, const CloudReferenceImage& reference,
                         const std::vector<std::pair<std::string, std::vector<float>>>& columns);

// The luminance (Rec. 709) of each pixel of `image`, as one column for writeCloudPixelsCsv.
std::vector<float> cloudPixelLuminance(const Image& image);

}  // namespace firmament
