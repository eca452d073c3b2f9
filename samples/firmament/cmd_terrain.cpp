// firmament terrain SCENE --out DIR: resolves the scene's terrain without rendering and writes what it
// resolves to: heights.exr (one channel Y, metres above sea level, row 0 north), hillshade.png (a
// preview) and terrain.json (extent, spacing, height range, source, fallback, time).
#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "atmosphere/atmosphere_settings.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "core/png_io.h"
#include "core/scene.h"
#include "samples/firmament/command.h"
#include "terrain/height_map_file.h"
#include "terrain/scene_terrain.h"
#include "terrain/terrain_preview.h"

namespace firmament::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

int runTerrain(const Args& args) {
  const std::string scenePath = args.positionals.at(0);
  auto out = args.get("out");
  if (!out) throw InputError("firmament terrain: --out DIR is required");
  Scene scene = Scene::load(scenePath, args.all("set"));
  if (!scene.hasSection("terrain"))
    throw InputError(scenePath + ": the scene has no \"terrain\" section (the ground is the atmosphere's sphere)");
  const double planetRadius = AtmosphereSettings::fromScene(scene).bottomRadius;
  terrain::ResolvedTerrain resolved = terrain::resolveSceneTerrain(scene, planetRadius);
  const terrain::HeightField& field = resolved.field;

  fs::path dir(*out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("cannot create the output folder '" + dir.string() + "': " + ec.message());
  terrain::writeHeightFieldExr(dir / "heights.exr", field, {{"terrain:scene", scene.source()}});
  const std::vector<uint8_t> rgb = terrain::hillshadeRgb(field);
  writePng(dir / "hillshade.png", field.nx, field.ny, 3, rgb.data());

  const terrain::TerrainSettings& s = resolved.settings;
  json report;
  report["scene"] = scene.source();
  report["kind"] = terrain::kindName(s.kind);
  report["source"] = resolved.source;
  report["samples"] = {field.nx, field.ny};
  report["spacing_m"] = {field.dx, field.dy};
  report["extent_m"] = {{"west", field.x0}, {"south", field.y0}, {"east", field.xMax()}, {"north", field.yMax()}};
  report["min_height_m"] = field.minHeight();
  report["max_height_m"] = field.maxHeight();
  report["location_height_m"] = s.locationHeight_m;
  report["outside_height_m"] = field.outsideHeight;
  report["planet_radius_m"] = planetRadius;
  report["fallback"] = terrain::fallbackName(s.fallback);
  report["data_fraction"] = resolved.dataFraction;
  report["resolve_seconds"] = resolved.seconds;
  report["frame"] = "gnomonic plane tangent at the location: x east, y north (m); heights above sea level (m)";
  if (s.kind == terrain::TerrainKind::Procedural) {
    report["style"] = terrain::styleParameters(s.procedural.style).name;
    report["seed"] = s.procedural.seed;
  } else {
    report["file"] = s.file.string();
  }
  writeTextFileAtomically(dir / "terrain.json", report.dump(2) + "\n");
  logInfo("terrain: " + resolved.source + ", " + std::to_string(field.nx) + "x" + std::to_string(field.ny) +
          " samples, heights " + std::to_string(field.minHeight()) + " to " + std::to_string(field.maxHeight()) +
          " m, " + std::to_string(resolved.seconds) + " s; wrote heights.exr, hillshade.png, terrain.json to " +
          dir.string());
  return kExitOk;
}

const CommandRegistration registration(Command{
    "terrain",
    "resolve the scene's terrain without rendering: heights (EXR, metres), a hillshade (PNG) and terrain.json",
    "terrain SCENE --out DIR [--set /PATH=VALUE ...]",
    {{"out", "DIR", "output folder (created if missing)", false, 'o'}, setOption()},
    1,
    1,
    runTerrain});

}  // namespace
}  // namespace firmament::cli
