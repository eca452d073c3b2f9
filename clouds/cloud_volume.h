#pragma once
// The cloud field on a voxel lattice: the frame, the region and the value of a voxel that
// `firmament export-vdb` writes as an OpenVDB grid (clouds/vdb_export.h; docs/clouds.md, "Export to
// OpenVDB"). Free of OpenVDB, so that only clouds/vdb_export.cpp compiles its headers.
//
// Frame ("local ENU"): metres in the east-north-up frame of the camera's ground point (the point of
// the ground sphere, radius R, straight below the camera): x east, y north, z up, origin on the ground.
// It is the cloud frame of common/cloud_density.glsl (planet-centred, z through the scene's location)
// moved down by R, p = (x, y, R + z): a rigid translation, so straight rays stay straight and the
// shells keep the planet's curvature (a layer's base at a horizontal distance d from the origin lies
// about d^2 / (2 R) lower: 7.9 m at 10 km, 31 m at 20 km).
//
// Lattice: voxel (i, j, k) is the cube [i h, (i + 1) h] x [j h, (j + 1) h] x [k h, (k + 1) h] with its
// value taken at its centre ((i + 1/2) h, (j + 1/2) h, (k + 1/2) h). It is anchored at the origin, so
// exports with the same voxel size line up whatever their regions; a region takes every voxel whose
// cube overlaps it.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "clouds/reference_clouds.h"
#include "common/cloud_density.glsl"

namespace firmament {

// A box in the local ENU frame (m) and the lattice's voxel size h (m).
struct CloudVolumeRegion {
  double west_m = -10000.0, south_m = -10000.0, east_m = 10000.0, north_m = 10000.0;
  double bottom_m = 0.0, top_m = 0.0;
  double voxelSize_m = 50.0;
};

// Inclusive voxel index bounds of a region.
struct CloudVoxelBox {
  glm::ivec3 min{0}, max{-1};
  uint64_t count() const;  // 0 when empty
};

// Limits of a region (checked by validateCloudVolumeRegion): voxel size in [kMin, kMax], every bound
// within kCloudVolumeMaxExtent_m of the origin, at most kCloudVolumeMaxVoxels voxels sampled.
inline constexpr double kCloudVolumeMinVoxel_m = 1.0;
inline constexpr double kCloudVolumeMaxVoxel_m = 10000.0;
inline constexpr double kCloudVolumeMaxExtent_m = 1.0e6;
inline constexpr uint64_t kCloudVolumeMaxVoxels = 1000000000ull;

// InputError (naming the region's field and what is allowed) for a non-finite bound, west >= east,
// south >= north, bottom >= top, a voxel size or extent out of range, or too many voxels.
void validateCloudVolumeRegion(const CloudVolumeRegion& region);

// The voxels whose cubes overlap the region (the region must be valid).
CloudVoxelBox cloudVoxelBox(const CloudVolumeRegion& region);

// Centre of voxel ijk in the local ENU frame (m).
glm::dvec3 cloudVoxelCentre(glm::ivec3 ijk, double voxelSize_m);

// Local ENU (m) -> the cloud frame (planet-centred, m) for a ground sphere of radius groundRadius_m.
inline glm::dvec3 cloudFrameFromLocalEnu(glm::dvec3 enu, double groundRadius_m) {
  return glm::dvec3(enu.x, enu.y, groundRadius_m + enu.z);
}

// Sets region.bottom_m and top_m to the layers' extent over the region's horizontal box: from the
// lowest point of the lowest base (at the box's point farthest from the z axis: the shells curve down
// with the planet) to the highest point of the highest top (at the point nearest the axis). No layers:
// one voxel of height above the ground (bottom 0, top voxelSize_m), where the field is 0.
void fitCloudVolumeHeights(CloudVolumeRegion& region, const std::vector<shared::CloudLayer>& layers,
                           double groundRadius_m);

// The default region: the square of half-width halfWidth_m centred on the origin, voxel size
// voxelSize_m, heights fitted to the layers (fitCloudVolumeHeights).
CloudVolumeRegion defaultCloudVolumeRegion(const std::vector<shared::CloudLayer>& layers, double groundRadius_m,
                                           double halfWidth_m = 10000.0, double voxelSize_m = 50.0);

// The voxel's value: the extinction of all layers (m^-1; grey in the visible, so also at 550 nm) at
// its centre, as the path tracer and (in float) the GPU march evaluate it.
inline double cloudVoxelExtinction(const CloudMedium& medium, glm::ivec3 ijk, double voxelSize_m) {
  return medium.extinction(cloudFrameFromLocalEnu(cloudVoxelCentre(ijk, voxelSize_m), medium.groundRadius()));
}

}  // namespace firmament
