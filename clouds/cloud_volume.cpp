#include "clouds/cloud_volume.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace firmament {
namespace {

std::string metres(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.9g m", v);
  return buffer;
}

// Voxel index range [lo, hi] of the cubes [i h, (i + 1) h] that overlap [a, b] (a < b); a cube that only
// touches the interval at a face is not taken.
void indexRange(double a, double b, double h, int& lo, int& hi) {
  lo = int(std::floor(a / h));
  hi = int(std::ceil(b / h)) - 1;
  if (hi < lo) hi = lo;
}

}  // namespace

uint64_t CloudVoxelBox::count() const {
  if (max.x < min.x || max.y < min.y || max.z < min.z) return 0;
  return uint64_t(max.x - min.x + 1) * uint64_t(max.y - min.y + 1) * uint64_t(max.z - min.z + 1);
}

void validateCloudVolumeRegion(const CloudVolumeRegion& r) {
  const std::pair<const char*, double> bounds[] = {{"west", r.west_m},   {"south", r.south_m},   {"east", r.east_m},
                                                   {"north", r.north_m}, {"bottom", r.bottom_m}, {"top", r.top_m}};
  for (const auto& [name, value] : bounds)
    if (!std::isfinite(value) || std::abs(value) > kCloudVolumeMaxExtent_m)
      throw InputError(std::string("cloud volume: ") + name + " = " + metres(value) + "; allowed: finite, within " +
                       metres(kCloudVolumeMaxExtent_m) + " of the origin");
  if (!(r.west_m < r.east_m))
    throw InputError("cloud volume: west (" + metres(r.west_m) + ") must be less than east (" + metres(r.east_m) +
                     "); allowed: west < east");
  if (!(r.south_m < r.north_m))
    throw InputError("cloud volume: south (" + metres(r.south_m) + ") must be less than north (" + metres(r.north_m) +
                     "); allowed: south < north");
  if (!(r.bottom_m < r.top_m))
    throw InputError("cloud volume: bottom (" + metres(r.bottom_m) + ") must be less than top (" + metres(r.top_m) +
                     "); allowed: bottom < top");
  if (!(r.voxelSize_m >= kCloudVolumeMinVoxel_m && r.voxelSize_m <= kCloudVolumeMaxVoxel_m))
    throw InputError("cloud volume: voxel size " + metres(r.voxelSize_m) +
                     "; allowed: " + metres(kCloudVolumeMinVoxel_m) + " to " + metres(kCloudVolumeMaxVoxel_m));
  const uint64_t n = cloudVoxelBox(r).count();
  if (n > kCloudVolumeMaxVoxels)
    throw InputError("cloud volume: " + std::to_string(n) + " voxels; allowed: at most " +
                     std::to_string(kCloudVolumeMaxVoxels) + " (a larger voxel size or a smaller region)");
}

CloudVoxelBox cloudVoxelBox(const CloudVolumeRegion& r) {
  CloudVoxelBox box;
  indexRange(r.west_m, r.east_m, r.voxelSize_m, box.min.x, box.max.x);
  indexRange(r.south_m, r.north_m, r.voxelSize_m, box.min.y, box.max.y);
  indexRange(r.bottom_m, r.top_m, r.voxelSize_m, box.min.z, box.max.z);
  return box;
}

glm::dvec3 cloudVoxelCentre(glm::ivec3 ijk, double h) { return (glm::dvec3(ijk) + 0.5) * h; }

void fitCloudVolumeHeights(CloudVolumeRegion& r, const std::vector<shared::CloudLayer>& layers, double groundRadius_m) {
  if (layers.empty()) {
    r.bottom_m = 0.0;
    r.top_m = r.voxelSize_m;
    return;
  }
  double bottomRadius = layers.front().bottom_radius, topRadius = layers.front().top_radius;
  for (const shared::CloudLayer& l : layers) {
    bottomRadius = std::min(bottomRadius, double(l.bottom_radius));
    topRadius = std::max(topRadius, double(l.top_radius));
  }
  // Squared horizontal distances from the z axis of the box's farthest and nearest points.
  const auto farthest = [](double a, double b) { return std::max(std::abs(a), std::abs(b)); };
  const auto nearest = [](double a, double b) {
    return a <= 0.0 && b >= 0.0 ? 0.0 : std::min(std::abs(a), std::abs(b));
  };
  const double far2 = std::pow(farthest(r.west_m, r.east_m), 2) + std::pow(farthest(r.south_m, r.north_m), 2);
  const double near2 = std::pow(nearest(r.west_m, r.east_m), 2) + std::pow(nearest(r.south_m, r.north_m), 2);
  // The sphere of radius rho at horizontal distance d lies at z = sqrt(rho^2 - d^2) - R.
  r.bottom_m = std::sqrt(std::max(bottomRadius * bottomRadius - far2, 0.0)) - groundRadius_m;
  r.top_m = std::sqrt(std::max(topRadius * topRadius - near2, 0.0)) - groundRadius_m;
}

CloudVolumeRegion defaultCloudVolumeRegion(const std::vector<shared::CloudLayer>& layers, double groundRadius_m,
                                           double halfWidth_m, double voxelSize_m) {
  CloudVolumeRegion r;
  r.west_m = r.south_m = -halfWidth_m;
  r.east_m = r.north_m = halfWidth_m;
  r.voxelSize_m = voxelSize_m;
  fitCloudVolumeHeights(r, layers, groundRadius_m);
  return r;
}

}  // namespace firmament
