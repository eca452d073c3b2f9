#pragma once
// Height maps as image files: a grey PNG (16-bit, or 8-bit) whose values map linearly onto a height
// range, or an EXR whose one channel (Y, Z, R or its only channel) holds metres; placed on the plane as
// a rectangle in metres (terrain/terrain_settings.h, HeightMapPlacement). Row 0 of an image is its
// northern edge; the height field's row 0 is the south (the reader flips).
//
// The inverse, writeHeightFieldExr, is what `firmament terrain` writes: one FLOAT channel "Y"
// (metres above sea level, so any EXR viewer shows it as grey) and string attributes for its placement
// (terrain:x0_m, terrain:y0_m, terrain:dx_m, terrain:dy_m, terrain:units, terrain:source).
#include <filesystem>
#include <map>
#include <string>

#include "terrain/height_field.h"
#include "terrain/terrain_settings.h"

namespace firmament::terrain {

// The image's own samples at its pixel centres. A missing or unreadable file, a colour PNG, an EXR
// without a usable channel, a non-finite EXR height or one outside [kLowestHeight_m,
// kHighestHeight_m] is an InputError naming the file (and the pixel).
HeightField readHeightMap(const std::filesystem::path& file, const HeightMapPlacement& placement);

void writeHeightFieldExr(const std::filesystem::path& file, const HeightField& field,
                         const std::map<std::string, std::string>& metadata = {});

// The height of a 16-bit value v: minHeight + (maxHeight − minHeight) v / 65535 (8-bit: / 255).
double heightOfPngValue(unsigned value, int bitDepth, const HeightMapPlacement& placement);

}  // namespace firmament::terrain
