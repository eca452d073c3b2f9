#include "eval/cloud_pixels_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/color.h"

namespace firmament {

void writeCloudPixelsCsv(const std::filesystem::path& file, const SceneView& view, const CloudReferenceImage& reference,
                         const std::vector<std::pair<std::string, std::vector<float>>>& columns) {
  const bool halves = reference.luminanceOddPaths.size() == reference.luminance.size();
  std::string csv = "x,y,scattering_angle_deg,reference_luminance,reference_standard_error,reference_transmittance";
  if (halves) csv += ",reference_luminance_even_paths,reference_luminance_odd_paths";
  for (const auto& [name, luminance] : columns) {
    std::string column = name;
    std::replace(column.begin(), column.end(), ',', ';');
    csv += "," + column;
  }
  csv += "\n";
  char line[96];
  const int width = reference.image.width;
  for (size_t i = 0; i < reference.image.pixelCount(); ++i) {
    const int x = int(i % size_t(width)), y = int(i / size_t(width));
    bool valid = true;
    const glm::dvec3 dir = shared::cameraRayDirection(view.camera, glm::dvec2(x + 0.5, y + 0.5), valid);
    const double angle =
        valid ? std::acos(std::clamp(glm::dot(dir, view.sunDirection), -1.0, 1.0)) * 180.0 / shared::kPi : -1.0;
    std::snprintf(line, sizeof(line), "%d,%d,%.2f,%.6g,%.6g,%.4f", x, y, angle, reference.luminance[i],
                  reference.luminanceStandardError[i], reference.image.pixels[4 * i + 3]);
    csv += line;
    if (halves) {
      std::snprintf(line, sizeof(line), ",%.6g,%.6g", reference.luminanceEvenPaths[i], reference.luminanceOddPaths[i]);
      csv += line;
    }
    for (const auto& column : columns) {
      std::snprintf(line, sizeof(line), ",%.6g", double(column.second[i]));
      csv += line;
    }
    csv += "\n";
  }
  writeTextFileAtomically(file, csv);
}

std::vector<float> cloudPixelLuminance(const Image& image) {
  std::vector<float> luminance(image.pixelCount());
  for (size_t i = 0; i < luminance.size(); ++i)
    luminance[i] = float(luminanceRec709(image.pixels.data() + size_t(image.channels) * i));
  return luminance;
}

}  // namespace firmament
