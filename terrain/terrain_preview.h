#pragma once
// A picture of a height field for a person to look at (not a rendering): a hillshade, lit from the
// north-west 45° above the horizon as cartographers do (Imhof 1982, "Cartographic relief
// presentation"; the slope–aspect formula of Burrough & McDonnell 1998, "Principles of GIS", §9.3),
// times a hypsometric tint from the field's lowest (green) to highest (white) height.
#include <cstdint>
#include <vector>

#include "terrain/height_field.h"

namespace firmament::terrain {

// RGB bytes, nx × ny, row 0 at the north (as images are).
std::vector<uint8_t> hillshadeRgb(const HeightField& field);

}  // namespace firmament::terrain
