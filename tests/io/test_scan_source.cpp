// Scan sources: a dataset's gives exactly what the dataset loads (scans
// saved in the world frame moved back to the sensor), memory's the clouds
// it holds; both name the scan asked for when it does not exist.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "hba/io/dataset.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "test_dataset_support.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

// Three scans in the "scans" layout; scan 1 has no intensity.
std::vector<PointCloud> writeThreeScans(const fs::path& dir, const std::vector<Pose>& poses, bool in_world) {
  std::vector<PointCloud> sensor(3);
  fs::create_directories(dir / "Scans");
  for (std::size_t i = 0; i < 3; ++i) {
    PointCloud stored;
    for (int k = 0; k < 50; ++k) {
      const Vec3f p(0.5f * static_cast<float>(k), 1.0f + static_cast<float>(i),
                    -0.25f * static_cast<float>(k));
      if (i == 1) {
        sensor[i].add(p);
      } else {
        sensor[i].add(p, static_cast<float>(k));
      }
      const Vec3f kept = in_world ? (poses[i] * p.cast<double>()).cast<float>() : p;
      if (i == 1) {
        stored.add(kept);
      } else {
        stored.add(kept, static_cast<float>(k));
      }
    }
    writePcd(dir / "Scans" / ("00000" + std::to_string(i) + ".pcd"), stored);
  }
  writePoses(dir / "odom_poses.txt", Trajectory{poses, {}}, PoseFormat::Kitti);
  return sensor;
}

std::vector<Pose> threePoses() {
  return {Pose::identity(), Pose(Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())), Vec3(2.0, 1.0, 0.0)),
          Pose(Quat(Eigen::AngleAxisd(-0.2, Vec3::UnitX())), Vec3(4.0, -1.0, 0.5))};
}

TEST(DatasetScanSource, GivesTheScansAsTheyAreStored) {
  test::TempDir dir;
  const std::vector<PointCloud> sensor = writeThreeScans(dir.path(), threePoses(), false);
  const Dataset dataset = Dataset::open(dir.path());
  const DatasetScanSource source(dataset);
  ASSERT_EQ(source.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) test::expectSameCloud(sensor[i], source.load(i));
}

TEST(DatasetScanSource, ScansSavedInTheWorldComeInTheSensorFrame) {
  test::TempDir dir;
  const std::vector<PointCloud> sensor = writeThreeScans(dir.path(), threePoses(), true);
  DatasetOverrides overrides;
  overrides.scans_in_world = true;
  const Dataset dataset = Dataset::open(dir.path(), overrides);
  const DatasetScanSource source(dataset);
  for (std::size_t i = 0; i < 3; ++i) {
    const PointCloud scan = source.load(i);
    test::expectSameCloud(dataset.loadScan(i), scan);
    test::expectNearCloud(sensor[i], scan, 1e-5f);
  }
}

TEST(DatasetScanSource, ParallelLoadsGiveTheSameScans) {
  test::TempDir dir;
  const std::vector<PointCloud> sensor = writeThreeScans(dir.path(), threePoses(), false);
  const Dataset dataset = Dataset::open(dir.path());
  const DatasetScanSource source(dataset);
  std::vector<std::vector<PointCloud>> loaded(4, std::vector<PointCloud>(3));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < loaded.size(); ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t i = 0; i < 3; ++i) loaded[t][i] = source.load(i);
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (const std::vector<PointCloud>& scans : loaded) {
    for (std::size_t i = 0; i < 3; ++i) test::expectSameCloud(sensor[i], scans[i]);
  }
}

TEST(ScanSources, AScanOutOfRangeIsAnErrorThatSaysWhich) {
  test::TempDir dir;
  writeThreeScans(dir.path(), threePoses(), false);
  const Dataset dataset = Dataset::open(dir.path());
  test::expectErrorMentioning([&] { DatasetScanSource(dataset).load(3); },
                              {dir.path().string(), "scan 3", "3 scans"});
  test::expectErrorMentioning([&] { MemoryScanSource(std::vector<PointCloud>(2)).load(2); },
                              {"in memory", "scan 2", "2 scans"});
}

TEST(MemoryScanSource, GivesTheCloudsItHolds) {
  const std::vector<PointCloud> clouds = {test::makeCloud(10, true), test::makeCloud(4, false), PointCloud()};
  const MemoryScanSource source(clouds);
  ASSERT_EQ(source.size(), 3u);
  for (std::size_t i = 0; i < clouds.size(); ++i) test::expectSameCloud(clouds[i], source.load(i));
  EXPECT_EQ(MemoryScanSource(std::vector<PointCloud>{}).size(), 0u);
}

TEST(ConcatenatedScanSource, GivesEachPartsScansInTurn) {
  const std::vector<PointCloud> a = {test::makeCloud(3, false), test::makeCloud(5, true)};
  const std::vector<PointCloud> b = {test::makeCloud(7, false)};
  const MemoryScanSource first(a), empty(std::vector<PointCloud>{}), second(b);
  const ConcatenatedScanSource whole({&first, &empty, &second});
  ASSERT_EQ(whole.size(), 3u);
  EXPECT_EQ(whole.starts(), (std::vector<std::size_t>{0, 2, 2, 3}));
  test::expectSameCloud(a[0], whole.load(0));
  test::expectSameCloud(a[1], whole.load(1));
  test::expectSameCloud(b[0], whole.load(2));
  test::expectErrorMentioning([&] { whole.load(3); }, {"sessions", "scan 3", "3 scans"});
}

// How large each scan is, cheaply, to share work out by: a dataset's file
// bytes, memory's points, a concatenation its part's.
TEST(ScanSources, TellHowLargeEachScanIs) {
  test::TempDir dir;
  writeThreeScans(dir.path(), threePoses(), false);
  const Dataset dataset = Dataset::open(dir.path());
  const DatasetScanSource source(dataset);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(source.sizeHint(i), static_cast<double>(fs::file_size(dataset.scanPath(i))));
  }
  EXPECT_LT(source.sizeHint(1), source.sizeHint(0));  // no intensity: fewer bytes
  const MemoryScanSource memory({test::makeCloud(10, true), PointCloud()});
  EXPECT_EQ(memory.sizeHint(0), 10.0);
  EXPECT_EQ(memory.sizeHint(1), 0.0);
  const ConcatenatedScanSource whole({&memory, &source});
  EXPECT_EQ(whole.sizeHint(0), 10.0);
  EXPECT_EQ(whole.sizeHint(4), source.sizeHint(2));
}

}  // namespace
}  // namespace hba::io
