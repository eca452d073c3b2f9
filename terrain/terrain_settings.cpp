#include "terrain/terrain_settings.h"

#include "core/error.h"

namespace firmament::terrain {
namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;

shared::vec3 colour(const Scene& scene, const std::string& pointer) {
  const nlohmann::json& a = scene.at(pointer);
  return {a.at(0).get<double>(), a.at(1).get<double>(), a.at(2).get<double>()};
}
}  // namespace

const char* kindName(TerrainKind kind) {
  switch (kind) {
    case TerrainKind::Procedural:
      return "procedural";
    case TerrainKind::Gdal:
      return "gdal";
    case TerrainKind::HeightMap:
      return "heightmap";
  }
  return "?";
}

const char* fallbackName(TerrainFallback fallback) {
  return fallback == TerrainFallback::Sphere ? "sphere" : "procedural";
}

TerrainSettings terrainSettingsFromScene(const Scene& scene) {
  TerrainSettings s;
  const std::string kind = scene.string("/terrain/kind");
  s.kind = kind == "gdal" ? TerrainKind::Gdal : kind == "heightmap" ? TerrainKind::HeightMap : TerrainKind::Procedural;
  s.locationHeight_m = scene.number("/location/height_m");
  s.procedural.style = styleFromName(scene.string("/terrain/style"));
  s.procedural.seed = uint64_t(scene.integer("/terrain/seed"));
  s.procedural.horizontalScale = scene.number("/terrain/horizontal_scale");
  s.procedural.verticalScale = scene.number("/terrain/vertical_scale");
  s.procedural.detail_m = scene.number("/terrain/detail_m");
  s.procedural.baseHeight = s.locationHeight_m;
  s.extent_m = scene.number("/terrain/extent_m");
  s.resolution = int(scene.integer("/terrain/resolution"));
  const std::string file = scene.string("/terrain/file");
  if (s.kind != TerrainKind::Procedural && file.empty())
    throw InputError(scene.source() + ": /terrain/file: found nothing, allowed: a file path (kind \"" + kind +
                     "\" reads its heights from a file)");
  if (!file.empty()) {
    std::filesystem::path p(file);
    // A relative path is relative to the scene file's folder (a scene given as text: the working folder).
    std::filesystem::path sceneFile(scene.source());
    if (p.is_relative() && sceneFile.has_parent_path() && std::filesystem::exists(sceneFile))
      p = sceneFile.parent_path() / p;
    s.file = p;
  }
  s.heightMap.width_m = scene.number("/terrain/heightmap/width_m");
  s.heightMap.length_m = scene.number("/terrain/heightmap/length_m");
  s.heightMap.centreEast_m = scene.number("/terrain/heightmap/centre_east_m");
  s.heightMap.centreNorth_m = scene.number("/terrain/heightmap/centre_north_m");
  s.heightMap.minHeight_m = scene.number("/terrain/heightmap/min_height_m");
  s.heightMap.maxHeight_m = scene.number("/terrain/heightmap/max_height_m");
  if (!(s.heightMap.maxHeight_m > s.heightMap.minHeight_m) && s.kind == TerrainKind::HeightMap)
    throw InputError(scene.source() + ": /terrain/heightmap/max_height_m: found " +
                     std::to_string(s.heightMap.maxHeight_m) + ", allowed: a number above min_height_m (" +
                     std::to_string(s.heightMap.minHeight_m) + ")");
  s.fallback =
      scene.string("/terrain/fallback") == "procedural" ? TerrainFallback::Procedural : TerrainFallback::Sphere;
  s.edgeBlend_m = scene.number("/terrain/edge_blend_m");
  shared::TerrainAlbedoParameters& a = s.albedo;
  a.rock = colour(scene, "/terrain/albedo/rock");
  a.vegetation = colour(scene, "/terrain/albedo/vegetation");
  a.snow = colour(scene, "/terrain/albedo/snow");
  a.treeLine = scene.number("/terrain/albedo/tree_line_m");
  a.treeLineTransition = scene.number("/terrain/albedo/tree_line_transition_m");
  a.vegetationMaxSlope = scene.number("/terrain/albedo/vegetation_max_slope_deg") * kDegree;
  a.snowLine = scene.number("/terrain/albedo/snow_line_m");
  a.snowLineTransition = scene.number("/terrain/albedo/snow_line_transition_m");
  a.snowMaxSlope = scene.number("/terrain/albedo/snow_max_slope_deg") * kDegree;
  a.slopeTransition = scene.number("/terrain/albedo/slope_transition_deg") * kDegree;
  return s;
}

}  // namespace firmament::terrain
