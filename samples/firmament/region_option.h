#pragma once
// The --region WEST,SOUTH,EAST,NORTH option of the commands that sample the clouds over a box of the
// local ENU frame (export-vdb, analyze clouds).
#include <string>

#include "clouds/cloud_volume.h"

namespace firmament::cli {

// Parses four finite numbers (m east and north of the camera's ground point), WEST < EAST, SOUTH < NORTH,
// each within kCloudVolumeMaxExtent_m, into region's horizontal bounds; InputError naming the option
// and what is allowed otherwise.
void parseRegion(const std::string& text, CloudVolumeRegion& region);

}  // namespace firmament::cli
