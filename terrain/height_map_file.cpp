#include "terrain/height_map_file.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/exr_io.h"
#include "core/png_io.h"

namespace firmament::terrain {
namespace fs = std::filesystem;

namespace {
std::string lowercaseExtension(const fs::path& file) {
  std::string e = file.extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}
}  // namespace

double heightOfPngValue(unsigned value, int bitDepth, const HeightMapPlacement& p) {
  const double top = bitDepth == 16 ? 65535.0 : 255.0;
  return p.minHeight_m + (p.maxHeight_m - p.minHeight_m) * (double(value) / top);
}

HeightField readHeightMap(const fs::path& file, const HeightMapPlacement& p) {
  const std::string extension = lowercaseExtension(file);
  int width = 0, height = 0;
  std::vector<float> values;  // row 0 north
  if (extension == ".png") {
    Grey16 png = readPngGrey16(file);
    width = png.width;
    height = png.height;
    values.resize(png.samples.size());
    for (size_t k = 0; k < values.size(); ++k) values[k] = float(heightOfPngValue(png.samples[k], png.bitDepth, p));
  } else if (extension == ".exr") {
    ExrChannel exr = readExrChannel(file, {"Y", "Z", "R", "height"});
    width = exr.width;
    height = exr.height;
    values = std::move(exr.values);
    for (size_t k = 0; k < values.size(); ++k) {
      const double h = values[k];
      if (!std::isfinite(h) || h < kLowestHeight_m || h > kHighestHeight_m)
        throw InputError("'" + file.string() + "': height " + number(h) + " m at pixel (" +
                         std::to_string(k % size_t(width)) + ", " + std::to_string(k / size_t(width)) +
                         ") is absurd; allowed: finite heights in [" + number(kLowestHeight_m) + ", " +
                         number(kHighestHeight_m) + "] m above sea level (an EXR height map holds metres)");
    }
  } else {
    throw InputError("'" + file.string() + "': a height map must be a .png (grey, 8 or 16 bits) or an .exr; found '" +
                     extension + "' (kind \"gdal\" reads other rasters)");
  }
  if (width < 2 || height < 2)
    throw InputError("'" + file.string() + "': a height map needs at least 2 x 2 pixels; it has " +
                     std::to_string(width) + " x " + std::to_string(height));
  const double dx = p.width_m / width, dy = p.length_m / height;
  HeightField field(width, height, p.centreEast_m - 0.5 * p.width_m + 0.5 * dx,
                    p.centreNorth_m - 0.5 * p.length_m + 0.5 * dy, dx, dy);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) field.at(i, j) = values[size_t(height - 1 - j) * size_t(width) + size_t(i)];
  field.source = "height map " + file.string();
  return field;
}

void writeHeightFieldExr(const fs::path& file, const HeightField& field,
                         const std::map<std::string, std::string>& metadata) {
  ExrChannel channel;
  channel.width = field.nx;
  channel.height = field.ny;
  channel.name = "Y";
  channel.values.resize(field.heights.size());
  for (int j = 0; j < field.ny; ++j)
    for (int i = 0; i < field.nx; ++i)
      channel.values[size_t(field.ny - 1 - j) * size_t(field.nx) + size_t(i)] = field.at(i, j);
  channel.metadata = metadata;
  channel.metadata["terrain:units"] = "metres above sea level; row 0 north, column 0 west";
  channel.metadata["terrain:x0_m"] = number(field.x0);
  channel.metadata["terrain:y0_m"] = number(field.y0);
  channel.metadata["terrain:dx_m"] = number(field.dx);
  channel.metadata["terrain:dy_m"] = number(field.dy);
  channel.metadata["terrain:source"] = field.source;
  writeExrChannel(file, channel);
}

}  // namespace firmament::terrain
