// hku1 written into ROS 1 bags by python3-rosbag as FAST-LIO2 records it
// (/cloud_registered_body + /Odometry): `hba optimize BAG` gives the folder
// run's poses and MME, and `hba extract` gives the folder back.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "bag_fixture.hpp"
#include "cli_runs.hpp"

namespace hba::rec {
namespace {
namespace fs = std::filesystem;

double mmeOf(const std::string& data, const fs::path& poses) {
  const test::CommandResult result =
      test::runCommand(test::hbaTool() + " -q mme " + data + " --poses " + poses.string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::istringstream words(result.output);
  std::string label;
  double mme = 0.0;
  words >> label >> mme;
  EXPECT_EQ(label, "MME") << result.output;
  return mme;
}

TEST(Ros1BagReal, Hku1BagGivesTheFolderRunsPosesAndMme) {
  const fs::path hku1 = test::sharedDataDir() / "hku1";
  if (!fs::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "../shared/data/hku1 is absent";
  test::TempDir dir;
  WRITE_BAG_OR_SKIP(hku1, dir / "hku1.bag", "--compression lz4");
  const std::string bag = (dir / "hku1.bag").string();
  const std::string bag_before = test::readText(bag);

  test::runOk(test::hbaTool() + " -q -j 2 optimize " + bag + " -o " + (dir / "from_bag").string() +
              " --no-render");
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + hku1.string() + " -o " +
              (dir / "from_folder").string() + " --no-render");
  // The bag's quaternions differ from the folder's rotation matrices in
  // the 16th digit, and that is all.
  const double rmse = test::evalRmse("ate", dir / "from_folder" / "poses_kitti.txt",
                                     dir / "from_bag" / "poses_kitti.txt", dir.path(), "--align none");
  EXPECT_LT(rmse, 1e-3);
  const double mme_bag = mmeOf(bag, dir / "from_bag" / "poses_kitti.txt");
  const double mme_folder = mmeOf(hku1.string(), dir / "from_folder" / "poses_kitti.txt");
  EXPECT_NEAR(mme_bag, mme_folder, 1e-3);
  EXPECT_LT(mme_bag, -3.0);

  // extract, then optimize the folder it wrote: the bag run's poses exactly.
  test::runOk(test::hbaTool() + " -q extract " + bag + " -o " + (dir / "extracted").string());
  EXPECT_EQ(test::fileContents(dir / "extracted" / "pcd").size(), 314u);
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + (dir / "extracted").string() + " -o " +
              (dir / "from_extracted").string() + " --no-render");
  EXPECT_EQ(test::readText(dir / "from_extracted" / "poses_kitti.txt"),
            test::readText(dir / "from_bag" / "poses_kitti.txt"));
  EXPECT_EQ(test::readText(bag), bag_before);  // the recording untouched
}

// FAST-LIO2's /cloud_registered holds the scans already moved into the
// world: recorded in place of the body-frame topic, the run is refused
// before any work, naming the flag that reads it.
TEST(Ros1BagReal, WorldFrameCloudsAreCaughtByTheConventionCheck) {
  const fs::path hku1 = test::sharedDataDir() / "hku1";
  if (!fs::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "../shared/data/hku1 is absent";
  test::TempDir dir;
  WRITE_BAG_OR_SKIP(hku1, dir / "world.bag", "--world-frame");
  const test::CommandResult refused =
      test::runCommand(test::hbaTool() + " -q -j 2 optimize " + (dir / "world.bag").string() + " -o " +
                       (dir / "out").string() + " --no-render");
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(refused.output.find("--scans-in-world"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // With the flag the scans are moved back by their poses: the map of the bag's
  // world-frame clouds is the body-frame folder's map.
  const double mme_world = mmeOf((dir / "world.bag").string() + " --scans-in-world", hku1 / "odom_poses.txt");
  const double mme_folder = mmeOf(hku1.string(), hku1 / "odom_poses.txt");
  EXPECT_NEAR(mme_world, mme_folder, 1e-3);
}

// Keyframes of hku1, every scan's pose asked for: one line per scan, and
// at the keyframes' stamps the keyframes' optimized poses.
TEST(Ros1BagReal, EveryScanGetsAPoseFromItsKeyframes) {
  const fs::path hku1 = test::sharedDataDir() / "hku1";
  if (!fs::exists(hku1 / "odom_poses.txt")) GTEST_SKIP() << "../shared/data/hku1 is absent";
  test::TempDir dir;
  WRITE_BAG_OR_SKIP(hku1, dir / "hku1.bag", "");
  test::runOk(test::hbaTool() + " -q -j 2 optimize " + (dir / "hku1.bag").string() + " -o " +
              (dir / "out").string() + " --keyframe-distance 1 --every-scan --no-render");
  const auto lines = [](const fs::path& file) {
    std::vector<std::string> kept;
    std::istringstream text(test::readText(file));
    for (std::string line; std::getline(text, line);) {
      if (!line.empty() && line[0] != '#') kept.push_back(line);
    }
    return kept;
  };
  const std::vector<std::string> keyframes = lines(dir / "out" / "poses_tum.txt");
  const std::vector<std::string> every = lines(dir / "out" / "every_scan_poses_tum.txt");
  EXPECT_EQ(every.size(), 314u);
  ASSERT_GT(keyframes.size(), 20u);
  ASSERT_LT(keyframes.size(), every.size());
  // At each keyframe's stamp, its pose (to rounding).
  const auto numbers = [](const std::string& line) {
    std::istringstream words(line);
    std::vector<double> values;
    for (double v; words >> v;) values.push_back(v);
    return values;
  };
  std::size_t found = 0;
  for (const std::string& keyframe : keyframes) {
    const std::vector<double> expected = numbers(keyframe);
    for (const std::string& line : every) {
      const std::vector<double> got = numbers(line);
      if (got.size() != expected.size() || std::abs(got[0] - expected[0]) > 1e-6) continue;
      ++found;
      for (std::size_t k = 1; k < got.size(); ++k) EXPECT_NEAR(got[k], expected[k], 1e-9) << line;
    }
  }
  EXPECT_EQ(found, keyframes.size());
}

TEST(Ros1BagReal, ABadRecordingWritesNothing) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 3);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "two.bag", "--second-cloud-topic");
  const std::string before = test::readText(dir / "two.bag");
  for (const std::string command : {"optimize", "extract"}) {
    const test::CommandResult result = test::runCommand(
        test::hbaTool() + " " + command + " " + (dir / "two.bag").string() + " -o " + (dir / "out").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("choose one with --cloud-topic"), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  // The recording itself as the output, even with --force: refused.
  const test::CommandResult onto_input =
      test::runCommand(test::hbaTool() + " extract " + (dir / "two.bag").string() +
                       " --cloud-topic /cloud_registered -o " + (dir / "two.bag").string() + " --force");
  EXPECT_EQ(onto_input.exit_code, 1) << onto_input.output;
  EXPECT_NE(onto_input.output.find("is the input recording"), std::string::npos) << onto_input.output;
  EXPECT_EQ(test::readText(dir / "two.bag"), before);
  test::runOk(test::hbaTool() + " -q extract " + (dir / "two.bag").string() +
              " --cloud-topic /cloud_registered -o " + (dir / "out").string());
  EXPECT_TRUE(fs::exists(dir / "out" / "pose.json"));
}

}  // namespace
}  // namespace hba::rec
