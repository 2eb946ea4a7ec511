// Pose files: reading the three formats, format detection, exact round trips,
// and an error naming file and line for every kind of bad line.
#include <gtest/gtest.h>

#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "test_dataset_support.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;
using test::expectErrorMentioning;

fs::path poseData(const std::string& name) { return test::dataDir() / "poses" / name; }

Trajectory randomTrajectory(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 100.0);
  Trajectory trajectory;
  for (std::size_t i = 0; i < n; ++i) {
    const Quat q = Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
    trajectory.poses.emplace_back(q, Vec3(gauss(rng), gauss(rng), gauss(rng) / 3.0));
    trajectory.stamps.push_back(1.6e9 + i / 7.0);
  }
  return trajectory;
}

TEST(PoseFile, ReadsHbaLinesWithoutTrailingNewlineAndRenormalizes) {
  const Trajectory t = readPoses(poseData("hba_no_trailing_newline.json"), PoseFormat::Hba);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_FALSE(t.hasStamps());
  EXPECT_TRUE(t.poses[0].t.isApprox(Vec3(1, 2, 3)));
  EXPECT_NEAR(t.poses[0].q.w(), 1.0, 1e-15);  // "2 0 0 0" renormalized
  EXPECT_TRUE(t.poses[1].t.isApprox(Vec3(-1.5, 0.25, 0.4)));
  EXPECT_NEAR(t.poses[1].q.z(), -1.0, 1e-15);  // qw qx qy qz = 0 0 0 -3
  EXPECT_NEAR(t.poses[1].q.norm(), 1.0, 1e-15);
}

TEST(PoseFile, DetectsTheFormatFromTheNumberCount) {
  EXPECT_EQ(detectPoseFormat(poseData("hba_no_trailing_newline.json")), PoseFormat::Hba);
  EXPECT_EQ(detectPoseFormat(poseData("kitti_rounded.txt")), PoseFormat::Kitti);
  EXPECT_EQ(detectPoseFormat(poseData("tum_with_comments.txt")), PoseFormat::Tum);
  EXPECT_EQ(readPoses(poseData("tum_with_comments.txt")).size(), 2u);
}

TEST(PoseFile, KittiRotationsAreReorthonormalizedAndTrailingBlankLinesIgnored) {
  const Trajectory t = readPoses(poseData("kitti_rounded.txt"), PoseFormat::Kitti);
  ASSERT_EQ(t.size(), 2u);
  const Mat3 r = t.poses[0].R();
  EXPECT_LT((r.transpose() * r - Mat3::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r(0, 1), 0.001, 1e-5);  // still the rotation the file meant
  EXPECT_TRUE(t.poses[0].t.isApprox(Vec3(10, 20, 30)));
}

TEST(PoseFile, TumKeepsStampsAndSkipsComments) {
  const Trajectory t = readPoses(poseData("tum_with_comments.txt"), PoseFormat::Tum);
  ASSERT_EQ(t.size(), 2u);
  ASSERT_TRUE(t.hasStamps());
  EXPECT_DOUBLE_EQ(t.stamps[1], 1305031102.211214);
  EXPECT_DOUBLE_EQ(t.poses[1].t.x(), 1.3303);                                 // written "+1.3303"
  const Quat expected = Quat(-0.3248, 0.6574, 0.6126, -0.2949).normalized();  // w last in TUM
  EXPECT_NEAR(t.poses[0].q.angularDistance(expected), 0.0, 1e-12);
}

TEST(PoseFile, WindowsLineEndingsAndTabsAreFine) {
  test::TempDir dir;
  test::writeText(dir / "p.json", "1\t2 3 1 0 0 0\r\n4 5 6 1 0 0 0\r\n\r\n");
  const Trajectory t = readPoses(dir / "p.json");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.poses[1].t, Vec3(4, 5, 6));
}

TEST(PoseFile, EveryFormatRoundTripsExactly) {
  const Trajectory original = randomTrajectory(50, 7);
  test::TempDir dir;
  for (const PoseFormat format : {PoseFormat::Hba, PoseFormat::Kitti, PoseFormat::Tum}) {
    SCOPED_TRACE(hba::toString(format));
    const fs::path path = dir / ("poses_" + hba::toString(format) + ".txt");
    writePoses(path, original, format);
    EXPECT_EQ(detectPoseFormat(path), format);
    const Trajectory back = readPoses(path);
    ASSERT_EQ(back.size(), original.size());
    for (std::size_t i = 0; i < original.size(); ++i) {
      EXPECT_EQ(back.poses[i].t, original.poses[i].t) << "pose " << i;  // bit for bit
      EXPECT_LT(back.poses[i].q.angularDistance(original.poses[i].q), 1e-13) << "pose " << i;
    }
    if (format == PoseFormat::Tum) {
      EXPECT_EQ(back.stamps, original.stamps);
    }
  }
}

TEST(PoseFile, TumWithoutStampsWritesThePoseIndexAsTime) {
  Trajectory trajectory = randomTrajectory(3, 1);
  trajectory.stamps.clear();
  test::TempDir dir;
  writePoses(dir / "t.txt", trajectory, PoseFormat::Tum);
  EXPECT_EQ(readPoses(dir / "t.txt", PoseFormat::Tum).stamps, (std::vector<double>{0, 1, 2}));
}

TEST(PoseFile, WritingRefusesAnEmptyTrajectoryAndLeavesNoFile) {
  test::TempDir dir;
  expectErrorMentioning([&] { writePoses(dir / "p.txt", Trajectory{}, PoseFormat::Kitti); },
                        {"p.txt", "empty"});
  EXPECT_FALSE(fs::exists(dir / "p.txt"));
  expectErrorMentioning(
      [&] { writePoses(dir / "missing" / "p.txt", randomTrajectory(2, 3), PoseFormat::Hba); }, {"missing"});
}

TEST(PoseFile, FormatNames) {
  for (const PoseFormat format : {PoseFormat::Hba, PoseFormat::Kitti, PoseFormat::Tum}) {
    EXPECT_EQ(parseEnum<PoseFormat>(hba::toString(format)), format);
  }
  expectErrorMentioning([] { parseEnum<PoseFormat>("csv"); }, {"csv", "hba, kitti or tum"});
}

TEST(PoseFile, MissingFileIsNamed) {
  expectErrorMentioning([] { readPoses("/nonexistent/odom.txt"); },
                        {"/nonexistent/odom.txt", "no such file"});
}

// One bad input, the format to read it as, and what the error must mention.
struct BadPoseFile {
  std::string name;
  std::string content;
  std::vector<std::string> mentions;
};
// Printed (and so in ctest's test names) by name, not as raw bytes.
void PrintTo(const BadPoseFile& bad, std::ostream* os) { *os << bad.name; }

class BadPoseFileTest : public ::testing::TestWithParam<BadPoseFile> {};

TEST_P(BadPoseFileTest, ThrowsNamingFileLineAndProblem) {
  const BadPoseFile& bad = GetParam();
  test::TempDir dir;
  const fs::path path = dir / "poses.txt";
  test::writeText(path, bad.content);
  std::vector<std::string> mentions = bad.mentions;
  mentions.push_back(path.string());
  expectErrorMentioning([&] { readPoses(path); }, mentions);
}

const std::string kIdentityHba = "0 0 0 1 0 0 0\n";
const std::string kIdentityKitti = "1 0 0 0 0 1 0 0 0 0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    PoseFile, BadPoseFileTest,
    ::testing::Values(
        BadPoseFile{"SixNumbers", kIdentityHba + "1 2 3 1 0 0\n", {"line 2", "expected 7", "found 6"}},
        BadPoseFile{"KittiShortLine",
                    kIdentityKitti + kIdentityKitti + "1 0 0 0 0 1 0 0 0 0 1\n",
                    {"line 3", "expected 12", "found 11"}},
        BadPoseFile{"NotANumber",
                    kIdentityHba + kIdentityHba + "0 0 abc 1 0 0 0\n",
                    {"line 3", "'abc' is not a number"}},
        BadPoseFile{"NumberWithJunk", "0 0 0 1.0x 0 0 0\n", {"line 1", "'1.0x'"}},
        BadPoseFile{"NaN", kIdentityHba + "0 nan 0 1 0 0 0\n", {"line 2", "NaN"}},
        BadPoseFile{"Inf", "0 0 0 1 0 0 -inf\n", {"line 1", "infinite"}}, BadPoseFile{"Empty", "", {"empty"}},
        BadPoseFile{"OnlyCommentsAndBlanks", "# nothing\n\n\n", {"empty"}},
        BadPoseFile{"ZeroQuaternion", kIdentityHba + "1 2 3 0 0 0 0\n", {"line 2", "zero length"}},
        BadPoseFile{"TinyQuaternion", "1 2 3 1e-9 0 0 1e-9\n", {"line 1", "zero length"}},
        BadPoseFile{"KittiZeroRotation", "0 0 0 1 0 0 0 2 0 0 0 3\n", {"line 1", "not a rotation"}},
        BadPoseFile{"KittiReflection", "-1 0 0 0 0 1 0 0 0 0 1 0\n", {"line 1", "reflection"}},
        BadPoseFile{"BlankLineBetweenPoses", kIdentityHba + "\n" + kIdentityHba, {"line 2", "blank"}},
        BadPoseFile{"UnknownNumberCount", "1 2 3 4 5\n", {"line 1", "cannot tell the pose format"}}),
    [](const ::testing::TestParamInfo<BadPoseFile>& case_info) { return case_info.param.name; });

TEST(PoseFile, ForcedFormatReportsTheCountMismatch) {
  expectErrorMentioning([] { readPoses(poseData("hba_no_trailing_newline.json"), PoseFormat::Kitti); },
                        {"hba_no_trailing_newline.json", "line 1", "expected 12", "found 7"});
}

}  // namespace
}  // namespace hba::io
