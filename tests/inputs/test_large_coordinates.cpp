// Coordinates far from the origin (UTM: 500 km east, 4000 km north) must give
// the same poses and the same map as the same data near the origin.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runs.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/ply.hpp"
#include "hba/io/pose_file.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

const Vec3 kUtmOffset(500000.0, 4000000.0, 120.0);

// A copy of `data` (scans linked, trajectory moved by `offset`) in `copy`.
void makeShiftedCopy(const fs::path& data, const std::string& scans, const std::string& poses,
                     const fs::path& copy, const Vec3& offset) {
  fs::create_directories(copy);
  fs::create_directory_symlink(fs::absolute(data / scans), copy / scans);
  Trajectory trajectory = io::readPoses(data / poses);
  trajectory.poses = translated(trajectory.poses, offset);
  io::writePoses(copy / poses, trajectory, io::detectPoseFormat(data / poses));
}

double mmeOf(const fs::path& data, const fs::path& poses) {
  const test::CommandResult result =
      test::runHba("-q mme " + test::quoted(data) + " --poses " + test::quoted(poses));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::size_t at = result.output.find("MME ");
  return at == std::string::npos ? 0.0 : std::stod(result.output.substr(at + 4));
}

// Optimizes `data` and its far-away copy; the poses must agree to 0.1 mm
// once moved back, and the maps' entropy must agree.
void expectSameResultFarAway(const fs::path& data, const std::string& scans, const std::string& poses) {
  test::TempDir dir;
  makeShiftedCopy(data, scans, poses, dir / "far", kUtmOffset);
  ASSERT_EQ(test::runOptimize(data, dir / "near_out", "--no-render", 2).exit_code, 0);
  const test::CommandResult far = test::runOptimize(dir / "far", dir / "far_out", "--no-render", 2);
  ASSERT_EQ(far.exit_code, 0) << far.output;

  const std::vector<Pose> near = test::readOptimizedPoses(dir / "near_out");
  const std::vector<Pose> back = translated(test::readOptimizedPoses(dir / "far_out"), -kUtmOffset);
  ASSERT_EQ(near.size(), back.size());
  // Moving the input rounds it by 1e-9 m; the iterations amplify that a little.
  EXPECT_LT(test::largestTranslation(near, back), 1e-4);
  EXPECT_LT(test::largestRotationDeg(near, back), 1e-3);
  EXPECT_NEAR(mmeOf(data, dir / "near_out" / "poses_kitti.txt"),
              mmeOf(dir / "far", dir / "far_out" / "poses_kitti.txt"), 1e-4);
}

TEST(LargeCoordinates, Hku1InUtmGivesTheSamePosesAndMap) {
  const fs::path data = test::sharedDataDir() / "hku1";
  if (!fs::exists(data)) GTEST_SKIP() << data << " not present";
  expectSameResultFarAway(data, "Scans", "odom_poses.txt");
}

TEST(LargeCoordinates, SimulatedDriveInUtmGivesTheSamePoses) {
  test::TempDir dir;
  const test::CommandResult sim =
      test::runHba("-q simulate --frames 60 --seed 3 -o " + test::quoted(dir / "sim"));
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  expectSameResultFarAway(dir / "sim", "pcd", "pose.json");
}

// `hba map` keeps millimetres far from the origin: the map is written with
// float64 coordinates, and reads back as the near map moved by the offset.
TEST(LargeCoordinates, MapFarAwayIsTheNearMapMoved) {
  test::TempDir dir;
  ASSERT_EQ(test::runHba("-q simulate --frames 20 --seed 4 -o " + test::quoted(dir / "sim")).exit_code, 0);
  makeShiftedCopy(dir / "sim", "pcd", "pose.json", dir / "far", kUtmOffset);
  for (const char* name : {"map.pcd", "map.ply"}) {
    ASSERT_EQ(test::runHba("-q map " + test::quoted(dir / "sim") + " -o " +
                           test::quoted(dir / ("near_" + std::string(name))))
                  .exit_code,
              0);
    ASSERT_EQ(test::runHba("-q map " + test::quoted(dir / "far") + " -o " +
                           test::quoted(dir / ("far_" + std::string(name))))
                  .exit_code,
              0);
    const bool pcd = std::string(name) == "map.pcd";
    const PointCloud near = pcd ? io::readPcd(dir / "near_map.pcd") : io::readPly(dir / "near_map.ply");
    const PointCloud far = pcd ? io::readPcd(dir / "far_map.pcd") : io::readPly(dir / "far_map.ply");
    ASSERT_EQ(near.size(), far.size()) << name;
    EXPECT_FALSE(far.origin.isZero()) << name;  // read back relative to an origin
    double worst = 0.0;
    for (std::size_t i = 0; i < near.size(); ++i) {
      worst = std::max(worst, (far.world(i) - kUtmOffset - near.world(i)).norm());
    }
    EXPECT_LT(worst, 1e-4) << name;
  }
}

// Writers and readers: a cloud with an origin round-trips in every encoding.
TEST(LargeCoordinates, CloudWithAnOriginRoundTripsInEveryEncoding) {
  PointCloud cloud;
  cloud.origin = kUtmOffset + Vec3(0.25, -0.5, 0.0);
  cloud.add(Vec3f(0.001f, 2.5f, -1.0f), 7.0f);
  cloud.add(Vec3f(-30.123f, 0.0f, 4.75f), 9.0f);
  test::TempDir dir;
  const auto check = [&](const PointCloud& read, const std::string& what) {
    ASSERT_EQ(read.size(), cloud.size()) << what;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_LT((read.world(i) - cloud.world(i)).norm(), 1e-5) << what;
      EXPECT_EQ(read.intensity[i], cloud.intensity[i]) << what;
    }
  };
  for (io::PcdEncoding encoding :
       {io::PcdEncoding::Ascii, io::PcdEncoding::Binary, io::PcdEncoding::BinaryCompressed}) {
    io::writePcd(dir / "c.pcd", cloud, encoding);
    check(io::readPcd(dir / "c.pcd"), "pcd " + std::to_string(static_cast<int>(encoding)));
  }
  for (io::PlyEncoding encoding : {io::PlyEncoding::Ascii, io::PlyEncoding::BinaryLittleEndian}) {
    io::writePly(dir / "c.ply", cloud, encoding);
    check(io::readPly(dir / "c.ply"), "ply " + std::to_string(static_cast<int>(encoding)));
  }
  // Neither (0,0,0) placeholders nor a stray point decide the origin: the bulk does.
  PointCloud messy;
  messy.origin = kUtmOffset;
  messy.add(Vec3f((-kUtmOffset).cast<float>()), 0.0f);                   // (0, 0, 0)
  messy.add(Vec3f((Vec3(5e7, 0, 0) - kUtmOffset).cast<float>()), 0.0f);  // a stray value
  for (int i = 0; i < 5; ++i) messy.add(Vec3f(0.001f * static_cast<float>(i), 0.25f, 1.5f), 1.0f);
  for (io::PcdEncoding encoding : {io::PcdEncoding::Ascii, io::PcdEncoding::Binary}) {
    io::writePcd(dir / "m.pcd", messy, encoding);
    const PointCloud read = io::readPcd(dir / "m.pcd");
    EXPECT_LT((read.origin - kUtmOffset).norm(), 5.0);  // the median's whole metres
    ASSERT_EQ(read.size(), messy.size());
    EXPECT_LT((read.world(6) - messy.world(6)).norm(), 1e-5);
  }
  // A float64 cloud near the origin needs no origin.
  PointCloud near;
  near.add(Vec3f(1.0f, 2.0f, 3.0f), 1.0f);
  near.origin = Vec3(1e-3, 0.0, 0.0);  // any non-zero origin writes float64
  io::writePcd(dir / "n.pcd", near);
  EXPECT_TRUE(io::readPcd(dir / "n.pcd").origin.isZero());
}

}  // namespace
}  // namespace hba
