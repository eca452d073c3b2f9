// `firmament analyze clouds SCENE --out DIR`: the scene's cloud field seen from above, measured the way
// observations of real cloud fields are (eval/cloud_field_statistics.h, docs/clouds/shapes.md): cloud
// fraction, the number of clouds, the area-perimeter fractal dimension, the size distribution's
// exponent, the largest cloud and the cloud tops. Writes stats.json, clouds.csv (one row per cloud),
// optical_depth.exr and mask.png.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "clouds/cloud_settings.h"
#include "clouds/cloud_volume.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/log.h"
#include "core/png_io.h"
#include "core/scene.h"
#include "eval/cloud_field_statistics.h"
#include "gpu/context.h"
#include "samples/firmament/command.h"
#include "samples/firmament/region_option.h"
#include "sky/scene_cloud_medium.h"
#include "sky/scene_view.h"

namespace firmament::cli {
namespace {

namespace fs = std::filesystem;

// The weather map's square (51.2 km) around the camera's ground point, at 50 m per column: the scale of
// the smallest fair-weather cumuli (~100 m) in two columns.
constexpr double kDefaultHalfWidth_m = 25600.0;
constexpr double kDefaultPixel_m = 50.0;

int runAnalyze(const Args& args) {
  if (args.positionals.at(0) != "clouds")
    throw InputError("analyze: '" + args.positionals.at(0) + "' is not something to analyse; allowed: clouds");
  if (args.positionals.size() < 2) throw InputError("analyze clouds: SCENE is required");
  const std::string scenePath = args.positionals.at(1);
  const auto out = args.get("out");
  if (!out) throw InputError("analyze clouds: --out DIR is required");
  const double pixel = args.number("pixel-size", kDefaultPixel_m);
  if (!(pixel >= 10.0 && pixel <= 5000.0))
    throw InputError("option --pixel-size: " + formatNumber("%g", pixel) + " m; allowed: 10 to 5000 m");
  CloudFieldStatisticsOptions statistics;
  statistics.opticalDepthThreshold = args.number("tau", 1.0);
  if (!(statistics.opticalDepthThreshold > 0.0 && statistics.opticalDepthThreshold <= 1000.0))
    throw InputError("option --tau: " + formatNumber("%g", statistics.opticalDepthThreshold) +
                     "; allowed: an optical depth in (0, 1000]");
  const int threads = args.integer("threads", 0, 0, 1024);
  CloudVolumeRegion region;
  region.west_m = region.south_m = -kDefaultHalfWidth_m;
  region.east_m = region.north_m = kDefaultHalfWidth_m;
  if (auto text = args.get("region")) parseRegion(*text, region);
  region.voxelSize_m = pixel;
  const double columns =
      std::ceil((region.east_m - region.west_m) / pixel) * std::ceil((region.north_m - region.south_m) / pixel);
  if (columns > 16.0e6)
    throw InputError("options --region/--pixel-size: " + formatNumber("%.0f", columns) +
                     " columns; allowed: at most 16 million (raise --pixel-size or shrink the region)");

  const Scene scene = Scene::load(scenePath, args.all("set"));  // InputError (exit 2) on a bad scene or override
  if (!sceneHasCloudLayers(scene))
    throw InputError(scenePath + ": the scene has no cloud layers (/clouds/layers): nothing to analyse");
  const SceneView view = makeSceneView(scene);
  const double ground = sceneGroundRadius(scene, view);
  fitCloudVolumeHeights(region, sharedCloudLayers(CloudSettings::fromScene(scene), ground), ground);

  const fs::path dir(*out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("--out " + dir.string() + ": cannot create the folder: " + ec.message());

  gpu::ContextOptions contextOptions;
  contextOptions.device = args.getOr("device", "");
  gpu::Context context(contextOptions);
  logInfo("analyze clouds: baking the noise on " + context.description());
  const CloudMedium medium = sceneCloudMedium(scene, view, context);
  // Vertical steps of at most 25 m (half a default column), so that a cumulus a few hundred metres deep
  // is sampled by ten or more.
  const double dz = std::min(25.0, pixel / 2.0);
  const CloudColumnField field = sampleCloudColumns(medium, region, dz, 1e-4, threads);
  const CloudFieldStatistics s = analyzeCloudField(field, statistics);

  nlohmann::json j;
  j["scene"] = scenePath;
  j["utc"] = scene.string("/time/utc");
  j["region_m"] = {region.west_m, region.south_m, region.east_m, region.north_m};
  j["pixel_m"] = pixel;
  j["columns"] = {field.width, field.height};
  j["optical_depth_threshold"] = statistics.opticalDepthThreshold;
  j["cloud_fraction"] = s.cloudFraction;
  j["map_coverage"] = field.mapCoverage;
  j["clouds"] = s.clouds;
  j["fractal_dimension"] = {{"D", s.fractalDimension},
                            {"standard_error", s.fractalDimensionError},
                            {"clouds_in_fit", s.cloudsInDimensionFit},
                            {"observed", "1.35 +- 0.05 (Lovejoy 1982)"}};
  j["size_distribution"] = {{"beta", s.sizeExponent},
                            {"standard_error", s.sizeExponentError},
                            {"clouds_in_fit", s.cloudsInSizeFit},
                            {"L_min_m", s.sizeFitMin_m},
                            {"observed", "1.7-2.0 below a 1-2 km scale break (Neggers et al. 2003)"}};
  j["largest_cloud"] = {{"area_km2", s.largestArea_m2 * 1e-6}, {"size_km", s.largestSize_m * 1e-3}};
  j["cloud_top_m"] = {{"mean", s.meanTop_m}, {"p90", s.p90Top_m}, {"max", s.maxTop_m}};
  writeTextFileAtomically(dir / "stats.json", j.dump(2) + "\n");

  std::string csv = "area_m2,perimeter_m,size_m,top_m,touches_edge\n";
  for (const CloudObject& c : s.objects) {
    char row[160];
    std::snprintf(row, sizeof(row), "%.6g,%.6g,%.6g,%.6g,%d\n", c.area_m2, c.perimeter_m, c.size_m, c.top_m,
                  c.touchesEdge ? 1 : 0);
    csv += row;
  }
  writeTextFileAtomically(dir / "clouds.csv", csv);

  // The images with row 0 at the top (north), as every image the tool writes.
  ExrChannel depth{field.width, field.height, "Y", std::vector<float>(field.opticalDepth.size()), {}};
  std::vector<uint8_t> mask(field.opticalDepth.size());
  for (int row = 0; row < field.height; ++row)
    for (int i = 0; i < field.width; ++i) {
      const size_t from = size_t(field.height - 1 - row) * field.width + i, to = size_t(row) * field.width + i;
      depth.values[to] = field.opticalDepth[from];
      mask[to] = field.opticalDepth[from] > statistics.opticalDepthThreshold ? 255 : 0;
    }
  depth.metadata = {{"firmament:quantity", "vertical optical depth at 550 nm"},
                    {"firmament:pixel_m", formatNumber("%.9g", pixel)},
                    {"firmament:scene", scenePath}};
  writeExrChannel(dir / "optical_depth.exr", depth);
  writePng(dir / "mask.png", field.width, field.height, 1, mask.data());

  char line[400];
  std::snprintf(line, sizeof(line),
                "analyze clouds: fraction %.3f (the map's coverage %.3f), %d clouds, D %.3f +- %.3f (%d clouds), beta "
                "%.2f +- %.2f (%d "
                "clouds above %.0f m), largest %.2f km across, tops mean %.0f m, max %.0f m; wrote %s",
                s.cloudFraction, field.mapCoverage, s.clouds, s.fractalDimension, s.fractalDimensionError,
                s.cloudsInDimensionFit, s.sizeExponent, s.sizeExponentError, s.cloudsInSizeFit, s.sizeFitMin_m,
                s.largestSize_m * 1e-3, s.meanTop_m, s.maxTop_m, dir.string().c_str());
  logInfo(line);
  return kExitOk;
}

const CommandRegistration registration(Command{
    "analyze",
    "measure a scene's cloud field from above: fraction, count, fractal dimension, size distribution, tops",
    "analyze clouds SCENE --out DIR [--region W,S,E,N] [--pixel-size M] [--tau T] [--set /PATH=VALUE ...]",
    {{"out", "DIR", "output folder for stats.json, clouds.csv, optical_depth.exr, mask.png", false, 'o'},
     {"region", "W,S,E,N", "box in metres east and north of the camera's ground point (default +-25600)"},
     {"pixel-size", "M", "column spacing in metres (default 50)"},
     {"tau", "T", "vertical optical depth above which a column is cloud (default 1)"},
     {"threads", "N", "CPU threads for the columns (default: all cores)"},
     setOption(),
     deviceOption()},
    2,
    2,
    runAnalyze});

}  // namespace
}  // namespace firmament::cli
