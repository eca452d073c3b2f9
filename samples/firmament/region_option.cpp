#include "samples/firmament/region_option.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace firmament::cli {

void parseRegion(const std::string& text, CloudVolumeRegion& region) {
  char limit[32];
  std::snprintf(limit, sizeof(limit), "%.0f", kCloudVolumeMaxExtent_m);
  const std::string allowed =
      "; allowed: WEST,SOUTH,EAST,NORTH in metres east and north of the camera's ground "
      "point, WEST < EAST, SOUTH < NORTH, each within " +
      std::string(limit) + " m (e.g. -10000,-10000,10000,10000)";
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v))
      throw InputError("option --region: '" + item + "' in '" + text + "' is not a number" + allowed);
    values.push_back(v);
  }
  if (values.size() != 4 || (!text.empty() && text.back() == ','))
    throw InputError("option --region: '" + text + "' has " + std::to_string(values.size()) + " value(s), not 4" +
                     allowed);
  for (double v : values)
    if (std::abs(v) > kCloudVolumeMaxExtent_m)
      throw InputError("option --region: '" + text + "' is too large" + allowed);
  if (!(values[0] < values[2]))
    throw InputError("option --region: WEST must be less than EAST in '" + text + "'" + allowed);
  if (!(values[1] < values[3]))
    throw InputError("option --region: SOUTH must be less than NORTH in '" + text + "'" + allowed);
  region.west_m = values[0], region.south_m = values[1], region.east_m = values[2], region.north_m = values[3];
}

}  // namespace firmament::cli
