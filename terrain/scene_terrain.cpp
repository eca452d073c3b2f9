#include "terrain/scene_terrain.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "astro/geodetic.h"
#include "core/error.h"
#include "terrain/gdal_raster.h"
#include "terrain/height_map_file.h"
#include "terrain/terrain_fill.h"
#include "terrain/terrain_frame.h"

namespace firmament::terrain {
namespace {
std::string number(double v) {
  std::ostringstream s;
  s.precision(8);
  s << v;
  return s.str();
}
}  // namespace

void checkHeightLimits(const HeightField& field, const std::string& source, const std::string& what) {
  const double lo = field.minHeight(), hi = field.maxHeight();
  if (lo >= kLowestHeight_m && hi <= kHighestHeight_m) return;
  throw InputError(source + ": /terrain: " + what + " reaches heights from " + number(lo) + " to " + number(hi) +
                   " m, outside the allowed [" + number(kLowestHeight_m) + ", " + number(kHighestHeight_m) +
                   "] m above sea level (Challenger Deep to above Everest)");
}

ResolvedTerrain resolveSceneTerrain(const Scene& scene, double planetRadius) {
  const TerrainSettings s = terrainSettingsFromScene(scene);
  return resolveSceneTerrain(scene, planetRadius, TileRegion::centred(0.0, 0.0, s.extent_m, s.resolution));
}

ResolvedTerrain resolveSceneTerrain(const Scene& scene, double planetRadius, const TileRegion& region) {
  const auto start = std::chrono::steady_clock::now();
  ResolvedTerrain out;
  out.settings = terrainSettingsFromScene(scene);
  out.region = region;
  const TerrainSettings& s = out.settings;
  const auto location = astro::GeodeticLocation::fromDegrees(
      scene.number("/location/latitude_deg"), scene.number("/location/longitude_deg"), s.locationHeight_m);
  const TerrainFrame frame(location, planetRadius);
  const ProceduralTerrainField procedural(s.procedural);
  const double finest = 2.0 * std::max(region.dx, region.dy);
  const std::string styleWords = std::string("the ") + styleParameters(s.procedural.style).name + " style (relief " +
                                 number(styleParameters(s.procedural.style).relief_m) + " m x vertical_scale " +
                                 number(s.procedural.verticalScale) + ") around /location/height_m " +
                                 number(s.locationHeight_m);
  auto fallback = [&](double x, double y) {
    return s.fallback == TerrainFallback::Sphere ? s.locationHeight_m : procedural.height(x, y, finest);
  };
  if (s.kind == TerrainKind::Procedural) {
    out.field = procedural.tile(region);
    checkHeightLimits(out.field, scene.source(), styleWords);
    out.source = out.field.source;
  } else if (s.kind == TerrainKind::Gdal) {
    const GdalRaster raster = readGdalRaster(s.file);
    const GdalPlacement placement(raster, frame);
    placement.checkCoversLocation(scene.source());
    out.field = placement.resample(region);
    out.dataFraction = fillFromFallback(out.field, fallback, s.edgeBlend_m);
    if (s.fallback == TerrainFallback::Procedural)
      checkHeightLimits(out.field, scene.source(), "the fallback, " + styleWords);
    out.source = out.field.source;
  } else {
    const HeightField map = readHeightMap(s.file, s.heightMap);
    const double halfX = 0.5 * map.dx, halfY = 0.5 * map.dy;
    if (!(map.x0 - halfX <= 0.0 && map.xMax() + halfX >= 0.0 && map.y0 - halfY <= 0.0 && map.yMax() + halfY >= 0.0))
      throw InputError(scene.source() + ": /terrain/heightmap: the height map '" + s.file.string() +
                       "' does not cover the scene: it spans east " + number(map.x0 - halfX) + " to " +
                       number(map.xMax() + halfX) + " m and north " + number(map.y0 - halfY) + " to " +
                       number(map.yMax() + halfY) +
                       " m of the location; allowed: a placement that contains the "
                       "location (0, 0)");
    out.field = resampleField(map, region, halfX, halfY);
    out.dataFraction = fillFromFallback(out.field, fallback, s.edgeBlend_m);
    if (s.fallback == TerrainFallback::Procedural)
      checkHeightLimits(out.field, scene.source(), "the fallback, " + styleWords);
    out.source = map.source;
  }
  out.field.outsideHeight = s.locationHeight_m;
  out.field.source = out.source;
  checkHeightField(out.field);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace firmament::terrain
