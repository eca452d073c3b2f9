#pragma once
// The cloud field as an OpenVDB file, for Blender, Houdini or any path tracer (`firmament export-vdb`;
// docs/clouds.md, "Export to OpenVDB"). vdb_export.cpp is the only file of the project that includes
// OpenVDB (its headers take ~20 s to compile) and is a library of its own, firmament_clouds_vdb, that
// only the tool and its test link; this header has no OpenVDB types.
//
// The file holds one grid: a FloatGrid named "density", class fog volume, background 0, whose values
// are the clouds' extinction coefficient sigma_t (m^-1; grey in the visible, stated at 550 nm) of all
// layers at the voxel centres (clouds/cloud_volume.h: cloudVoxelExtinction, the path tracer's medium
// in double, stored as float). Only non-zero voxels are active (stored); constant blocks are pruned to
// tiles. The transform maps index (i, j, k) to the voxel's centre ((i + 1/2) h, (j + 1/2) h,
// (k + 1/2) h) in the local ENU frame (m, z up). Grid metadata: unit "m^-1", quantity, wavelength_nm
// 550, frame (a sentence), voxel_size_m, ground_radius_m, region_min_m / region_max_m (the region asked
// for, local ENU), and the caller's strings (the scene path, ...).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "clouds/cloud_volume.h"
#include "clouds/reference_clouds.h"

namespace firmament {

struct CloudVdbOptions {
  CloudVolumeRegion region;
  int threads = 0;                                            // 0: all cores; the values do not depend on it
  std::vector<std::pair<std::string, std::string>> metadata;  // extra string metadata, e.g. {"scene", path}
};

struct CloudVdbSummary {
  uint64_t sampledVoxels = 0;  // voxels of the region (each evaluated once; none without layers)
  uint64_t activeVoxels = 0;   // non-zero voxels, all stored
  double maxExtinction = 0.0;  // m^-1
  // Bounds of the active voxels' cubes (local ENU, m); both 0 when there are none.
  glm::dvec3 activeMin{0.0}, activeMax{0.0};
  double samplingSeconds = 0.0, writingSeconds = 0.0;
  int threads = 0;
  uintmax_t fileBytes = 0;
};

// The frame in words, as written into the grid's "frame" metadata.
extern const char* const kCloudVdbFrame;

// Samples `medium` over options.region and writes the grid to `path` atomically (a temporary file in
// the same folder, renamed when complete: an error leaves no file and an existing one unchanged).
// An empty field (no layers, coverage 0) gives a grid with no active voxels. Throws InputError for an
// invalid region (validateCloudVolumeRegion) or a missing folder, RuntimeError for a non-finite
// extinction or a failed write. progress(done, total) counts voxels, called from the workers in turn.
CloudVdbSummary writeCloudVdb(const std::filesystem::path& path, const CloudMedium& medium,
                              const CloudVdbOptions& options,
                              const std::function<void(uint64_t done, uint64_t total)>& progress = {});

}  // namespace firmament
