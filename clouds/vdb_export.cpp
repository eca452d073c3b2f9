#include "clouds/vdb_export.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include "core/atomic_file.h"
#include "core/error.h"

namespace firmament {

const char* const kCloudVdbFrame =
    "local ENU of the camera's ground point, metres: x east, y north, z up, origin on the ground sphere "
    "straight below the camera (z-up; Houdini, y-up: rotate -90 degrees about x)";

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// floor(a / b) for b > 0.
int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

struct WorkerResult {
  openvdb::FloatGrid::Ptr grid;
  double maxExtinction = 0.0;
  uint64_t nonFinite = 0;
};

}  // namespace

CloudVdbSummary writeCloudVdb(const std::filesystem::path& path, const CloudMedium& medium,
                              const CloudVdbOptions& options, const std::function<void(uint64_t, uint64_t)>& progress) {
  const CloudVolumeRegion& region = options.region;
  validateCloudVolumeRegion(region);
  openvdb::initialize();  // idempotent and thread-safe

  CloudVdbSummary summary;
  const Clock::time_point start = Clock::now();
  const CloudVoxelBox box = cloudVoxelBox(region);
  const double h = region.voxelSize_m;
  summary.sampledVoxels = box.count();

  // Work items: slabs of 8 rows (y) aligned to OpenVDB's 8^3 leaf nodes, so every leaf is written by
  // one worker's grid and merging the grids only moves nodes. No layers: nothing to sample.
  constexpr int kLeaf = 8;
  const int firstSlab = floorDiv(box.min.y, kLeaf), lastSlab = floorDiv(box.max.y, kLeaf);
  const int slabs = medium.layers().empty() ? 0 : lastSlab - firstSlab + 1;
  const int requested = options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const int workers = std::max(1, std::min(requested, slabs));
  summary.threads = workers;

  std::atomic<int> nextSlab{firstSlab};
  std::mutex progressMutex;
  uint64_t done = 0;
  const uint64_t rowVoxels = uint64_t(box.max.x - box.min.x + 1) * uint64_t(box.max.z - box.min.z + 1);
  std::vector<WorkerResult> results(static_cast<size_t>(workers));
  auto work = [&](size_t worker) {
    WorkerResult& result = results[worker];
    result.grid = openvdb::FloatGrid::create(0.0f);
    if (slabs == 0) return;
    openvdb::FloatGrid::Accessor voxels = result.grid->getAccessor();
    for (int slab = nextSlab++; slab <= lastSlab; slab = nextSlab++) {
      const int y0 = std::max(slab * kLeaf, box.min.y), y1 = std::min(slab * kLeaf + kLeaf - 1, box.max.y);
      for (int y = y0; y <= y1; ++y)
        for (int z = box.min.z; z <= box.max.z; ++z)
          for (int x = box.min.x; x <= box.max.x; ++x) {
            const double sigma = cloudVoxelExtinction(medium, glm::ivec3(x, y, z), h);
            if (!std::isfinite(sigma)) {
              ++result.nonFinite;
              continue;
            }
            const float value = float(sigma);
            if (value > 0.0f) {
              voxels.setValue(openvdb::Coord(x, y, z), value);
              result.maxExtinction = std::max(result.maxExtinction, sigma);
            }
          }
      if (progress) {
        std::lock_guard<std::mutex> lock(progressMutex);
        done += uint64_t(y1 - y0 + 1) * rowVoxels;
        progress(done, summary.sampledVoxels);
      }
    }
  };
  {
    std::vector<std::thread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(work, size_t(w));
    work(0);
    for (std::thread& t : pool) t.join();
  }

  openvdb::FloatGrid::Ptr grid = results[0].grid;
  uint64_t nonFinite = results[0].nonFinite;
  summary.maxExtinction = results[0].maxExtinction;
  for (size_t w = 1; w < results.size(); ++w) {
    grid->tree().merge(results[w].grid->tree(), openvdb::MERGE_ACTIVE_STATES);
    nonFinite += results[w].nonFinite;
    summary.maxExtinction = std::max(summary.maxExtinction, results[w].maxExtinction);
  }
  if (nonFinite > 0)
    throw RuntimeError("export-vdb: the cloud extinction is not finite at " + std::to_string(nonFinite) +
                       " voxel(s); nothing was written");
  openvdb::tools::prune(grid->tree());  // constant leaves -> tiles (tolerance 0: values unchanged)
  summary.activeVoxels = grid->activeVoxelCount();
  if (summary.activeVoxels > 0) {
    const openvdb::CoordBBox active = grid->evalActiveVoxelBoundingBox();
    summary.activeMin = glm::dvec3(active.min().x(), active.min().y(), active.min().z()) * h;
    summary.activeMax = (glm::dvec3(active.max().x(), active.max().y(), active.max().z()) + 1.0) * h;
  }
  summary.samplingSeconds = secondsSince(start);

  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(h);
  transform->postTranslate(openvdb::Vec3d(0.5 * h));  // index (i, j, k) -> centre ((i + 1/2) h, ...)
  grid->setTransform(transform);
  grid->setCreator("firmament export-vdb");
  grid->insertMeta("unit", openvdb::StringMetadata("m^-1"));
  grid->insertMeta("quantity",
                   openvdb::StringMetadata("cloud extinction coefficient sigma_t, all layers, at the voxel centres"));
  grid->insertMeta("wavelength_nm", openvdb::DoubleMetadata(550.0));
  grid->insertMeta("frame", openvdb::StringMetadata(kCloudVdbFrame));
  grid->insertMeta("voxel_size_m", openvdb::DoubleMetadata(h));
  grid->insertMeta("ground_radius_m", openvdb::DoubleMetadata(medium.groundRadius()));
  grid->insertMeta("region_min_m",
                   openvdb::Vec3DMetadata(openvdb::Vec3d(region.west_m, region.south_m, region.bottom_m)));
  grid->insertMeta("region_max_m", openvdb::Vec3DMetadata(openvdb::Vec3d(region.east_m, region.north_m, region.top_m)));
  for (const auto& [key, value] : options.metadata) grid->insertMeta(key, openvdb::StringMetadata(value));

  const Clock::time_point writeStart = Clock::now();
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    try {
      openvdb::io::File file(tmp.string());
      file.write(openvdb::GridCPtrVec{grid});
      file.close();
    } catch (const openvdb::Exception& e) {
      throw RuntimeError("export-vdb: cannot write " + path.string() + ": " + e.what());
    }
  });
  summary.writingSeconds = secondsSince(writeStart);
  std::error_code ec;
  summary.fileBytes = std::filesystem::file_size(path, ec);
  if (ec) summary.fileBytes = 0;
  return summary;
}

}  // namespace firmament
