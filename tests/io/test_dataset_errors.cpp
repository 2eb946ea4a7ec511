// Dataset discovery on hand-made folders: the fallbacks it allows and a clear
// error, naming files and counts, for everything it refuses.
#include <gtest/gtest.h>

#include <cstdio>

#include "hba/io/dataset.hpp"
#include "test_dataset_support.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;
using test::expectErrorMentioning;
using test::kittiPoseLines;
using test::makeScans;
using test::writeText;

TEST(DatasetErrors, MissingFolder) {
  expectErrorMentioning([] { Dataset::open("/nonexistent/sequence"); },
                        {"/nonexistent/sequence", "not found"});
}

TEST(DatasetErrors, EmptyFolder) {
  test::TempDir dir;
  expectErrorMentioning([&] { Dataset::open(dir.path()); },
                        {dir.path().string(), "no scans found", "--scans"});
}

// Issue 57 item 20: a folder of .vtk scans got "no scan files" without
// naming what is there.
TEST(DatasetErrors, ScansOfAFormatHbaDoesNotReadAreNamed) {
  test::TempDir dir;
  fs::create_directories(dir / "scans");
  char name[16];
  for (int i = 0; i < 14; ++i) {
    std::snprintf(name, sizeof name, "%06d.vtk", i);
    writeText(dir / "scans" / name, "# vtk DataFile Version 3.0\n");
  }
  writeText(dir / "odom_poses.txt", kittiPoseLines(14));
  expectErrorMentioning([&] { Dataset::open(dir.path()); },
                        {"no scans found", "scans/ holds 14 .vtk files (000000.vtk ... 000013.vtk)",
                         "the folder itself holds 1 .txt file (odom_poses.txt) and 1 folder", ".pcd"});
  DatasetOverrides overrides;
  overrides.scans_dir = dir / "scans";
  expectErrorMentioning([&] { Dataset::open(dir.path(), overrides); },
                        {(dir / "scans").string(),
                         "no scan files in this folder: it holds 14 .vtk files (000000.vtk ... 000013.vtk); "
                         "hba reads scans as .pcd"});
}

TEST(DatasetErrors, ScansWithoutTrajectory) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "000001.pcd"});
  writeText(dir / "calib.txt", "P0: 1 2 3\n");  // not a trajectory candidate
  expectErrorMentioning([&] { Dataset::open(dir.path()); },
                        {"no trajectory file found", "odom_poses.txt", "--poses"});
}

TEST(DatasetErrors, CountMismatchNamesBothFilesAndCounts) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "000001.pcd", "000002.pcd"});
  writeText(dir / "odom_poses.txt", kittiPoseLines(2));
  expectErrorMentioning([&] { Dataset::open(dir.path()); },
                        {"3 scans", (dir / "Scans").string(), "2 poses", (dir / "odom_poses.txt").string()});
}

TEST(DatasetErrors, GapInNumbering) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "000001.pcd", "000003.pcd"});
  writeText(dir / "odom_poses.txt", kittiPoseLines(3));
  expectErrorMentioning([&] { Dataset::open(dir.path()); },
                        {"gap", "000001.pcd is followed by 000003.pcd", "number 2 is missing"});
}

TEST(DatasetErrors, DuplicateNumbers) {
  test::TempDir dir;
  makeScans(dir / "pcd", {"0.pcd", "1.pcd", "01.pcd"});
  writeText(dir / "pose.json", test::hbaPoseLines(3));
  expectErrorMentioning([&] { Dataset::open(dir.path()); }, {"1.pcd", "same scan number (1)", "01.pcd"});
}

TEST(DatasetErrors, MixedExtensions) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "000001.ply"});
  writeText(dir / "odom_poses.txt", kittiPoseLines(2));
  expectErrorMentioning([&] { Dataset::open(dir.path()); }, {"mixed scan formats"});
}

TEST(DatasetErrors, NameWithoutNumber) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "last.pcd"});
  writeText(dir / "odom_poses.txt", kittiPoseLines(2));
  expectErrorMentioning([&] { Dataset::open(dir.path()); }, {"last.pcd", "no number"});
}

TEST(DatasetErrors, TwoScanFoldersAreAmbiguous) {
  test::TempDir dir;
  makeScans(dir / "pcd", {"0.pcd"});
  makeScans(dir / "Scans", {"000000.pcd"});
  writeText(dir / "pose.json", test::hbaPoseLines(1));
  expectErrorMentioning([&] { Dataset::open(dir.path()); }, {"pcd", "Scans", "--scans"});
}

TEST(DatasetErrors, SeveralUnknownTrajectoriesAreAmbiguous) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd"});
  writeText(dir / "lio.txt", kittiPoseLines(1));
  writeText(dir / "slam.txt", kittiPoseLines(1));
  expectErrorMentioning([&] { Dataset::open(dir.path()); }, {"lio.txt", "slam.txt", "--poses"});
}

TEST(DatasetErrors, MissingOverrideIsNamed) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd"});
  DatasetOverrides overrides;
  overrides.poses_file = "nope.txt";
  expectErrorMentioning([&] { Dataset::open(dir.path(), overrides); }, {"nope.txt", "poses file not found"});
}

TEST(DatasetFallbacks, SingleUnknownTrajectoryIsUsedAndNoted) {
  test::TempDir dir;
  makeScans(dir / "clouds", {"scan_1.pcd", "scan_2.pcd"});
  writeText(dir / "lio.txt", kittiPoseLines(2));
  const Dataset d = Dataset::open(dir.path());
  EXPECT_EQ(d.posesFile().filename(), "lio.txt");
  EXPECT_EQ(d.scanPath(0).filename(), "scan_1.pcd");
  EXPECT_TRUE(test::anyNoteMentions(d, "lio.txt"));
}

TEST(DatasetFallbacks, ScansInTheFolderItselfAndKittiSequenceFile) {
  test::TempDir dir;
  makeScans(dir.path(), {"000000.bin", "000001.bin"});
  writeText(dir / "05.txt", kittiPoseLines(2));
  const Dataset d = Dataset::open(dir.path());
  EXPECT_EQ(d.scansDir(), dir.path());
  EXPECT_EQ(d.posesFile().filename(), "05.txt");
  EXPECT_EQ(d.layout(), "kitti");
  EXPECT_TRUE(d.calibrationFile().empty());  // no calib.txt: poses used as they are
}

TEST(DatasetFallbacks, TimesWithTheWrongCountAreIgnoredWithAWarning) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "000001.pcd"});
  writeText(dir / "odom_poses.txt", kittiPoseLines(2));
  writeText(dir / "times.txt", "1.0\n");
  const Dataset d = Dataset::open(dir.path());
  EXPECT_FALSE(d.trajectory().hasStamps());
  ASSERT_EQ(d.notes().size(), 1u);
  EXPECT_EQ(d.notes()[0].level, DatasetNote::Level::Warning);
  EXPECT_NE(d.notes()[0].text.find("times.txt"), std::string::npos);
}

TEST(DatasetFallbacks, HiddenAndForeignFilesAreIgnored) {
  test::TempDir dir;
  makeScans(dir / "Scans", {"000000.pcd", "000001.pcd", ".000002.pcd", "notes.txt"});
  writeText(dir / "odom_poses.txt", kittiPoseLines(2));
  EXPECT_EQ(Dataset::open(dir.path()).size(), 2u);
}

}  // namespace
}  // namespace hba::io
