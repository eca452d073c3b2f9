// `firmament export-vdb SCENE -o clouds.vdb`: the clouds' extinction field over a region as an OpenVDB
// grid named "density" (m^-1), for Blender, Houdini or any path tracer (docs/clouds/vdb-export.md; the
// grid's layout is in clouds/vdb_export.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "clouds/cloud_settings.h"
#include "clouds/cloud_volume.h"
#include "clouds/vdb_export.h"
#include "core/error.h"
#include "core/log.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "samples/firmament/command.h"
#include "samples/firmament/region_option.h"
#include "sky/scene_cloud_medium.h"
#include "sky/scene_view.h"

namespace firmament::cli {
namespace {

constexpr double kDefaultVoxel_m = 50.0;
constexpr double kDefaultHalfWidth_m = 10000.0;

int runExportVdb(const Args& args) {
  const std::string scenePath = args.positionals.at(0);
  const std::filesystem::path out =
      args.getOr("output", "out/" + std::filesystem::path(scenePath).stem().string() + "_clouds.vdb");
  if (out.extension() != ".vdb") throw InputError("-o " + out.string() + ": the output must end in .vdb");
  const double voxel = args.number("voxel-size", kDefaultVoxel_m);
  if (!(voxel >= kCloudVolumeMinVoxel_m && voxel <= kCloudVolumeMaxVoxel_m))
    throw InputError("option --voxel-size: " + formatNumber("%g", voxel) +
                     " m; allowed: " + formatNumber("%g", kCloudVolumeMinVoxel_m) + " to " +
                     formatNumber("%g", kCloudVolumeMaxVoxel_m) + " m");
  const int threads = args.integer("threads", 0, 0, 1024);
  // Read the numbers before the scene, so that a bad option fails fast.
  CloudVolumeRegion asked;
  if (auto region = args.get("region")) parseRegion(*region, asked);
  const std::optional<double> bottom =
      args.has("bottom") ? std::optional<double>(args.number("bottom", 0.0)) : std::nullopt;
  const std::optional<double> top = args.has("top") ? std::optional<double>(args.number("top", 0.0)) : std::nullopt;
  for (const auto& [name, value] : {std::pair{"bottom", bottom}, std::pair{"top", top}})
    if (value && std::abs(*value) > kCloudVolumeMaxExtent_m)
      throw InputError(std::string("option --") + name + ": " + formatNumber("%g", *value) + " m; allowed: within " +
                       formatNumber("%.0f", kCloudVolumeMaxExtent_m) + " m of the ground");
  if (bottom && top && !(*bottom < *top))
    throw InputError("options --bottom " + formatNumber("%g", *bottom) + " and --top " + formatNumber("%g", *top) +
                     ": --bottom must be less than --top (metres above the camera's ground point)");

  const Scene scene = Scene::load(scenePath, args.all("set"));  // InputError (exit 2) on a bad scene or override
  const SceneView view = makeSceneView(scene);
  const double ground = sceneGroundRadius(scene, view);
  // The layers (no GPU yet): the region and its checks come before the noise bake.
  const std::vector<shared::CloudLayer> layers = sceneHasCloudLayers(scene)
                                                     ? sharedCloudLayers(CloudSettings::fromScene(scene), ground)
                                                     : std::vector<shared::CloudLayer>{};

  // The region: the heights the options leave out fitted to the layers over the horizontal box.
  CloudVolumeRegion region = defaultCloudVolumeRegion(layers, ground, kDefaultHalfWidth_m, voxel);
  if (args.has("region")) {
    region.west_m = asked.west_m, region.south_m = asked.south_m, region.east_m = asked.east_m,
    region.north_m = asked.north_m;
    fitCloudVolumeHeights(region, layers, ground);
  }
  if (bottom) region.bottom_m = *bottom;
  if (top) region.top_m = *top;
  if (!(region.bottom_m < region.top_m))
    throw InputError("options --bottom/--top: the height range " + formatNumber("%g", region.bottom_m) + " to " +
                     formatNumber("%g", region.top_m) +
                     " m is empty; allowed: bottom < top (defaults: the layers' lowest "
                     "base to their highest top over the region)");
  const uint64_t voxels = cloudVoxelBox(region).count();
  if (voxels > kCloudVolumeMaxVoxels)
    throw InputError("options --voxel-size/--region/--bottom/--top: " + std::to_string(voxels) +
                     " voxels; allowed: at most " + std::to_string(kCloudVolumeMaxVoxels) +
                     " (raise --voxel-size or shrink the region)");

  std::unique_ptr<gpu::Context> context;
  CloudMedium medium = emptyCloudMedium(ground);
  if (sceneHasCloudLayers(scene)) {
    gpu::ContextOptions contextOptions;
    contextOptions.device = args.getOr("device", "");
    context = std::make_unique<gpu::Context>(contextOptions);
    logInfo("export-vdb: baking the noise on " + context->description());
    medium = sceneCloudMedium(scene, view, *context);
  } else {
    logInfo("export-vdb: " + scenePath + " has no cloud layers: the grid will be empty");
  }

  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec)
    throw InputError("-o " + out.string() + ": cannot create the folder " + folder.string() + ": " + ec.message());

  CloudVdbOptions options;
  options.region = region;
  options.threads = threads;
  options.metadata = {{"scene", scenePath}, {"scene_hash", scene.hash()}};
  options.metadata.push_back(
      {"location", "latitude_deg " + formatNumber("%.9g", scene.number("/location/latitude_deg")) + " longitude_deg " +
                       formatNumber("%.9g", scene.number("/location/longitude_deg")) + " height_m " +
                       formatNumber("%.9g", scene.number("/location/height_m"))});
  options.metadata.push_back({"utc", scene.string("/time/utc")});
  {
    char line[320];
    std::snprintf(line, sizeof(line),
                  "export-vdb: %zu layer(s), voxel %g m, x %g..%g, y %g..%g, z %g..%g m (local ENU), %llu voxels",
                  medium.layers().size(), region.voxelSize_m, region.west_m, region.east_m, region.south_m,
                  region.north_m, region.bottom_m, region.top_m, (unsigned long long)voxels);
    logInfo(line);
  }
  CloudVdbSummary summary;
  {
    Progress progress("export-vdb", voxels);
    summary = writeCloudVdb(out, medium, options, [&](uint64_t done, uint64_t) { progress.set(done); });
  }
  char line[640];
  if (summary.activeVoxels > 0) {
    std::snprintf(
        line, sizeof(line),
        "wrote %s: grid 'density' (sigma_t, m^-1, 550 nm), %llu active voxels of %llu (%.2f %%), voxel %g "
        "m, active bounds x %.0f..%.0f y %.0f..%.0f z %.0f..%.0f m (local ENU), max sigma_t %.4g m^-1; "
        "%.2f s sampling + %.2f s writing on %d thread(s), %.1f MiB",
        out.string().c_str(), (unsigned long long)summary.activeVoxels, (unsigned long long)summary.sampledVoxels,
        100.0 * double(summary.activeVoxels) / double(std::max<uint64_t>(summary.sampledVoxels, 1)), region.voxelSize_m,
        summary.activeMin.x, summary.activeMax.x, summary.activeMin.y, summary.activeMax.y, summary.activeMin.z,
        summary.activeMax.z, summary.maxExtinction, summary.samplingSeconds, summary.writingSeconds, summary.threads,
        double(summary.fileBytes) / (1024.0 * 1024.0));
  } else {
    std::snprintf(line, sizeof(line),
                  "wrote %s: grid 'density' (sigma_t, m^-1, 550 nm) with 0 active voxels (no cloud in the region); "
                  "%.2f s sampling + %.2f s writing",
                  out.string().c_str(), summary.samplingSeconds, summary.writingSeconds);
  }
  logInfo(line);
  return kExitOk;
}

const CommandRegistration registration{Command{
    "export-vdb",
    "the clouds' extinction field over a region as an OpenVDB grid 'density' (m^-1) for other renderers",
    "export-vdb SCENE [-o OUT.vdb] [--voxel-size M] [--region WEST,SOUTH,EAST,NORTH] [--bottom M] [--top M] "
    "[--set /PATH=VALUE]... [--threads N] [--device D]",
    {
        {"output", "OUT.vdb", "output file (default out/<scene>_clouds.vdb)", false, 'o'},
        {"voxel-size", "M", "voxel edge in metres (default 50; 1 to 10000)"},
        {"region", "W,S,E,N",
         "horizontal box in metres east/north of the camera's ground point (default -10000,-10000,10000,10000)"},
        {"bottom", "M", "lowest height in metres (default: the layers' lowest base over the region)"},
        {"top", "M", "highest height in metres (default: the layers' highest top)"},
        setOption(),
        {"threads", "N", "worker threads (default: all cores); the voxel values do not depend on it"},
        deviceOption(),
    },
    1,
    1,
    runExportVdb,
}};

}  // namespace
}  // namespace firmament::cli
