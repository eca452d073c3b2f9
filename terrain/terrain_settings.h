#pragma once
// The scene's /terrain section, read once into plain values (docs/scene.md lists every field with its
// default and range; the schema has checked them). A scene without the section has no terrain and
// none of this runs.
#include <array>
#include <filesystem>
#include <string>

#include "common/terrain_albedo.glsl"
#include "core/scene.h"
#include "terrain/procedural_terrain.h"

namespace firmament::terrain {

enum class TerrainKind { Procedural, Gdal, HeightMap };
enum class TerrainFallback { Sphere, Procedural };

// A height-map image's placement: a rectangle of the plane, centred (centreEast, centreNorth) metres
// from the location, width × length metres, row 0 at its northern edge; a PNG's 0 … 65535 (or 0 … 255)
// maps linearly onto minHeight … maxHeight, an EXR holds metres.
struct HeightMapPlacement {
  double width_m = 10000.0;
  double length_m = 10000.0;
  double centreEast_m = 0.0;
  double centreNorth_m = 0.0;
  double minHeight_m = 0.0;
  double maxHeight_m = 1000.0;
};

struct TerrainSettings {
  TerrainKind kind = TerrainKind::Procedural;
  ProceduralTerrain procedural;  // style, seed, scales, detail; baseHeight = /location/height_m
  double extent_m = 20000.0;     // side of the square region resolved around the location
  int resolution = 1024;         // samples per side of that region
  std::filesystem::path file;    // kind gdal / heightmap, resolved against the scene file's folder
  HeightMapPlacement heightMap;
  TerrainFallback fallback = TerrainFallback::Sphere;
  double edgeBlend_m = 1000.0;
  shared::TerrainAlbedoParameters albedo{};
  double locationHeight_m = 0.0;  // /location/height_m: the atmosphere's ground sphere
};

// Reads /terrain (the scene must have the section). A gdal or heightmap kind without a file is an
// InputError naming /terrain/file.
TerrainSettings terrainSettingsFromScene(const Scene& scene);

const char* kindName(TerrainKind kind);
const char* fallbackName(TerrainFallback fallback);

// The physical limits every height field is held to (m above sea level): the Challenger Deep
// (−10 935 m) and Everest (8 849 m), rounded outwards. A height outside them is bad input (a raster
// in feet or centimetres, an undeclared nodata value such as −32768, or scales that are too large).
inline constexpr double kLowestHeight_m = -11000.0;
inline constexpr double kHighestHeight_m = 9000.0;

}  // namespace firmament::terrain
