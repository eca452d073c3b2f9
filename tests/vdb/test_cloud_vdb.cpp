// `firmament export-vdb`'s writer (clouds/vdb_export.h): the file read back with OpenVDB holds one fog
// volume named "density" with the stated metadata and transform, and every voxel's value is the CPU
// medium's extinction at the voxel's centre (computed here from the file's own transform); only the
// non-zero voxels are stored; no cloud gives an empty grid; bad regions are refused and leave nothing.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "clouds/cloud_volume.h"
#include "clouds/vdb_export.h"
#include "core/error.h"
#include "sky/scene_cloud_medium.h"
#include "tests/clouds/cloud_test_support.h"
#include "tests/support/test_paths.h"

namespace firmament {
namespace {

class CloudVdb : public test::GpuTest {};

// The scene's medium with the small noise of the cloud tests (32^3 shape: the bake is fast on lavapipe).
CloudMedium mediumOf(const Scene& scene) {
  const SceneView view = makeSceneView(scene);
  return sceneCloudMedium(scene, view, test::GpuTest::context(), test::smallCloudOptions().cloudNoise);
}

openvdb::FloatGrid::Ptr readDensity(const std::filesystem::path& path) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  EXPECT_EQ(grids->size(), 1u);
  if (grids->empty()) return nullptr;
  openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
  EXPECT_TRUE(grid) << "the grid is not a FloatGrid: " << grids->front()->type();
  return grid;
}

std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A 6 x 4 km box through the whole cumulus layer (1500-4000 m), 100 m voxels: 60 x 40 x 27 voxels.
CloudVolumeRegion smallRegion() {
  CloudVolumeRegion r;
  r.west_m = -3000.0, r.east_m = 3000.0, r.south_m = -2000.0, r.north_m = 2000.0;
  r.bottom_m = 1400.0, r.top_m = 4100.0;
  r.voxelSize_m = 100.0;
  return r;
}

TEST_F(CloudVdb, GridHoldsTheMediumsExtinctionAtTheVoxelCentres) {
  const Scene scene = test::cloudScene();
  const CloudMedium medium = mediumOf(scene);
  const std::filesystem::path path = test::scratchDir("vdb_values") / "cumulus.vdb";
  CloudVdbOptions options;
  options.region = smallRegion();
  options.metadata = {{"scene", "scenes/test.json"}};
  const CloudVdbSummary summary = writeCloudVdb(path, medium, options);
  EXPECT_EQ(summary.sampledVoxels, 60u * 40u * 27u);

  const openvdb::FloatGrid::Ptr grid = readDensity(path);
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->getName(), "density");
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(grid->background(), 0.0f);
  EXPECT_EQ(grid->metaValue<std::string>("unit"), "m^-1");
  EXPECT_EQ(grid->metaValue<double>("wavelength_nm"), 550.0);
  EXPECT_EQ(grid->metaValue<std::string>("frame"), kCloudVdbFrame);
  EXPECT_EQ(grid->metaValue<std::string>("scene"), "scenes/test.json");
  EXPECT_EQ(grid->metaValue<double>("voxel_size_m"), 100.0);
  EXPECT_EQ(grid->metaValue<double>("ground_radius_m"), medium.groundRadius());
  EXPECT_EQ(grid->metaValue<openvdb::Vec3d>("region_min_m"), openvdb::Vec3d(-3000.0, -2000.0, 1400.0));
  // The transform: index (i, j, k) -> centre ((i + 1/2) h, (j + 1/2) h, (k + 1/2) h), h = 100 m.
  EXPECT_EQ(grid->voxelSize(), openvdb::Vec3d(100.0));
  EXPECT_EQ(grid->indexToWorld(openvdb::Coord(0, 0, 0)), openvdb::Vec3d(50.0, 50.0, 50.0));
  EXPECT_EQ(grid->indexToWorld(openvdb::Coord(-30, 19, 14)), openvdb::Vec3d(-2950.0, 1950.0, 1450.0));

  // Every voxel of the region: its value is the medium's extinction (all layers, double) at the world
  // position of its centre per the file's transform, to float round-off; active exactly where non-zero.
  openvdb::FloatGrid::ConstAccessor voxels = grid->getConstAccessor();
  uint64_t nonZero = 0, zeroInShell = 0;
  double maxExpected = 0.0;
  for (int k = 14; k <= 40; ++k)
    for (int j = -20; j <= 19; ++j)
      for (int i = -30; i <= 29; ++i) {
        const openvdb::Coord ijk(i, j, k);
        const openvdb::Vec3d world = grid->indexToWorld(ijk);
        const double expected = medium.extinction(
            cloudFrameFromLocalEnu(glm::dvec3(world.x(), world.y(), world.z()), medium.groundRadius()));
        const float value = voxels.getValue(ijk);
        ASSERT_NEAR(value, expected, 6e-8 * expected) << "voxel " << ijk;
        ASSERT_EQ(voxels.isValueOn(ijk), expected > 0.0) << "voxel " << ijk << " value " << expected;
        if (expected > 0.0)
          ++nonZero;
        else if (world.z() > 1600.0 && world.z() < 3900.0)
          ++zeroInShell;
        maxExpected = std::max(maxExpected, expected);
      }
  // A real field with gaps: both cloud and clear voxels inside the layer.
  EXPECT_GT(nonZero, 1000u);
  EXPECT_GT(zeroInShell, 1000u);
  EXPECT_EQ(grid->activeVoxelCount(), nonZero);  // nothing stored outside the region, no zeros stored
  EXPECT_EQ(summary.activeVoxels, nonZero);
  EXPECT_EQ(summary.maxExtinction, maxExpected);
  EXPECT_LE(maxExpected, shared::cloudMajorant(medium.layers()[0]));
  // Below the base there is no cloud.
  EXPECT_FALSE(voxels.isValueOn(openvdb::Coord(0, 0, 14)));
  EXPECT_EQ(voxels.getValue(openvdb::Coord(0, 0, 14)), 0.0f);
}

TEST_F(CloudVdb, ValuesDoNotDependOnTheThreadCount) {
  const CloudMedium medium = mediumOf(test::cloudScene());
  const std::filesystem::path dir = test::scratchDir("vdb_threads");
  CloudVdbOptions options;
  options.region = smallRegion();
  options.threads = 1;
  writeCloudVdb(dir / "one.vdb", medium, options);
  options.threads = 3;
  const CloudVdbSummary three = writeCloudVdb(dir / "three.vdb", medium, options);
  EXPECT_EQ(three.threads, 3);
  const openvdb::FloatGrid::Ptr a = readDensity(dir / "one.vdb"), b = readDensity(dir / "three.vdb");
  ASSERT_TRUE(a && b);
  ASSERT_GT(a->activeVoxelCount(), 0u);
  EXPECT_EQ(a->activeVoxelCount(), b->activeVoxelCount());
  openvdb::FloatGrid::ConstAccessor bv = b->getConstAccessor();
  for (auto it = a->cbeginValueOn(); it; ++it) {
    ASSERT_TRUE(bv.isValueOn(it.getCoord()));
    ASSERT_EQ(bv.getValue(it.getCoord()), *it);
  }
}

TEST_F(CloudVdb, NoCloudGivesAnEmptyGrid) {
  const std::filesystem::path dir = test::scratchDir("vdb_empty");
  // Coverage 0: the layer exists, its field is 0 everywhere.
  const CloudMedium medium = mediumOf(test::cloudScene({"/clouds/layers/0/coverage=0"}));
  CloudVdbOptions options;
  options.region = smallRegion();
  const CloudVdbSummary summary = writeCloudVdb(dir / "coverage0.vdb", medium, options);
  EXPECT_EQ(summary.activeVoxels, 0u);
  EXPECT_EQ(summary.maxExtinction, 0.0);
  openvdb::FloatGrid::Ptr grid = readDensity(dir / "coverage0.vdb");
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->getName(), "density");
  EXPECT_EQ(grid->activeVoxelCount(), 0u);
  EXPECT_TRUE(grid->tree().empty());

  // No layers at all (a scene without clouds): the default region, nothing sampled, an empty grid.
  const double ground = 6360000.0;
  options.region = defaultCloudVolumeRegion({}, ground, 10000.0, 1000.0);
  const CloudVdbSummary none = writeCloudVdb(dir / "none.vdb", emptyCloudMedium(ground), options);
  EXPECT_EQ(none.activeVoxels, 0u);
  grid = readDensity(dir / "none.vdb");
  ASSERT_TRUE(grid);
  EXPECT_EQ(grid->activeVoxelCount(), 0u);
}

TEST_F(CloudVdb, BadRegionIsRefusedAndLeavesTheTargetAsItWas) {
  const std::filesystem::path dir = test::scratchDir("vdb_bad");
  const std::filesystem::path target = dir / "kept.vdb";
  std::ofstream(target) << "old contents";
  const CloudMedium medium = emptyCloudMedium(6360000.0);
  struct Case {
    CloudVolumeRegion region;
    std::string fragment;
  };
  std::vector<Case> cases;
  CloudVolumeRegion r = smallRegion();
  r.west_m = 5000.0;  // > east
  cases.push_back({r, "west"});
  r = smallRegion();
  r.top_m = r.bottom_m;
  cases.push_back({r, "bottom"});
  r = smallRegion();
  r.voxelSize_m = 0.0;
  cases.push_back({r, "voxel size"});
  r = smallRegion();
  r.north_m = std::nan("");
  cases.push_back({r, "north"});
  r = smallRegion();
  r.voxelSize_m = 1.0;
  r.west_m = r.south_m = -100000.0;
  r.east_m = r.north_m = 100000.0;
  cases.push_back({r, "voxels"});
  for (const Case& c : cases) {
    CloudVdbOptions options;
    options.region = c.region;
    try {
      writeCloudVdb(target, medium, options);
      ADD_FAILURE() << "no error for a region that should fail with '" << c.fragment << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("allowed"), std::string::npos) << e.what();
    }
    EXPECT_EQ(fileText(target), "old contents");
  }
  // Only the target is in the folder: no temporary file was left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  // A missing folder: an InputError naming it, nothing created.
  CloudVdbOptions options;
  options.region = smallRegion();
  EXPECT_THROW(writeCloudVdb(dir / "missing" / "x.vdb", medium, options), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
}

TEST(CloudVolume, LatticeAndDefaultRegion) {
  CloudVolumeRegion r;
  r.west_m = -120.0, r.east_m = 130.0, r.south_m = 0.0, r.north_m = 100.0, r.bottom_m = 1000.0, r.top_m = 1001.0;
  r.voxelSize_m = 50.0;
  const CloudVoxelBox box = cloudVoxelBox(r);
  // Cubes [i h, (i + 1) h] overlapping the box: x -3..2 (-150..150), y 0..1 (a face at 100 m is not
  // an overlap), z 20..20.
  EXPECT_EQ(box.min, glm::ivec3(-3, 0, 20));
  EXPECT_EQ(box.max, glm::ivec3(2, 1, 20));
  EXPECT_EQ(box.count(), 12u);
  EXPECT_EQ(cloudVoxelCentre(glm::ivec3(-3, 0, 20), 50.0), glm::dvec3(-125.0, 25.0, 1025.0));

  // Default: +-10 km, from the base at the corners (14.14 km out: 15.7 m lower) to the top.
  const double ground = 6360000.0;
  shared::CloudLayer layer{};
  layer.bottom_radius = ground + 1500.0;
  layer.top_radius = ground + 4000.0;
  const CloudVolumeRegion d = defaultCloudVolumeRegion({layer}, ground);
  EXPECT_EQ(d.west_m, -10000.0);
  EXPECT_EQ(d.north_m, 10000.0);
  EXPECT_EQ(d.voxelSize_m, 50.0);
  EXPECT_NEAR(d.bottom_m, 1500.0 - 2.0e8 / (2.0 * (ground + 1500.0)), 0.01);
  EXPECT_DOUBLE_EQ(d.top_m, 4000.0);
  // The corner's base really is that low: the layer's bottom sphere passes through (10 km, 10 km, bottom).
  EXPECT_NEAR(glm::length(cloudFrameFromLocalEnu(glm::dvec3(10000.0, 10000.0, d.bottom_m), ground)),
              layer.bottom_radius, 1e-6);
  EXPECT_NO_THROW(validateCloudVolumeRegion(d));
  // A box off the axis, 20-30 km east, 5 km either side of north: the base is lowest at its far
  // corner (30 km, +-5 km), the top highest at its nearest point (20 km, 0).
  CloudVolumeRegion off;
  off.west_m = 20000.0, off.east_m = 30000.0, off.south_m = -5000.0, off.north_m = 5000.0;
  fitCloudVolumeHeights(off, {layer}, ground);
  EXPECT_NEAR(glm::length(cloudFrameFromLocalEnu(glm::dvec3(30000.0, -5000.0, off.bottom_m), ground)),
              layer.bottom_radius, 1e-6);
  EXPECT_NEAR(glm::length(cloudFrameFromLocalEnu(glm::dvec3(20000.0, 0.0, off.top_m), ground)), layer.top_radius, 1e-6);
  EXPECT_LT(off.top_m, 4000.0 - 31.0);  // 20 km out the top is 31 m below its height over the origin
  EXPECT_EQ(cloudVoxelBox(d).count(), 400u * 400u * uint64_t(std::ceil(4000.0 / 50.0) - std::floor(d.bottom_m / 50.0)));
}

}  // namespace
}  // namespace firmament
