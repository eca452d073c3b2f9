#pragma once
// The terrain a scene asks for, resolved to a height field over a region of the plane: the source
// (procedural, a GDAL raster, a height-map image) sampled there, the fallback filled in where the data
// ends (terrain/terrain_fill.h), and the atmosphere's ground sphere outside the region. This is what
// `firmament terrain` writes and what a renderer ray-casts.
//
// Part of firmament_terrain_gdal (it reads rasters through terrain/gdal_raster.h); it includes no GDAL
// header itself.
#include <string>

#include "core/scene.h"
#include "terrain/height_field.h"
#include "terrain/procedural_terrain.h"
#include "terrain/terrain_settings.h"

namespace firmament::terrain {

struct ResolvedTerrain {
  HeightField field;  // outsideHeight = /location/height_m (the atmosphere's ground sphere)
  TerrainSettings settings;
  TileRegion region;
  std::string source;         // what the heights are, in words
  double dataFraction = 1.0;  // share of the samples the raster or height map gave (1 for procedural)
  double seconds = 0.0;       // wall time of the resolution
};

// The scene's region: the square of /terrain/extent_m around the location, /terrain/resolution samples
// a side. planetRadius: the atmosphere's ground radius (AtmosphereSettings::bottomRadius).
ResolvedTerrain resolveSceneTerrain(const Scene& scene, double planetRadius);
// Any region (a tile a renderer asks for).
ResolvedTerrain resolveSceneTerrain(const Scene& scene, double planetRadius, const TileRegion& region);

// InputError when the field's heights leave [kLowestHeight_m, kHighestHeight_m]; `what` says where
// the heights came from (a style and its scales, a file).
void checkHeightLimits(const HeightField& field, const std::string& source, const std::string& what);

}  // namespace firmament::terrain
