// Recordings that parse but cannot be trusted as they are (issue #57): a
// FIFO among a rosbag2 folder's files, a storage file named twice, a bag
// left in WAL mode, a NaN position, a quaternion not of unit length, two
// poses at one stamp, stamps that run backwards, a PointCloud2 with more
// data than its points, /tf_static transforms that form a cycle. Each is
// refused with a sentence naming the file, the topic and the message, or
// read as a careful reader would, and the recording is left as it was.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "bag_fixture.hpp"
#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/rec/recording.hpp"

namespace hba::rec {
namespace {
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

using test::openError;

std::string datasetError(const fs::path& path, const io::DatasetOverrides& overrides = {}) {
  try {
    io::Dataset::open(path, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// `hba -j 1 <arguments>`, stopped after a minute: a hang fails the test.
test::CommandResult hba(const std::string& arguments) {
  return test::runCommand("timeout 60 " + quoted(test::cliPath()) + " -j 1 " + arguments);
}

#define EXPECT_HAS(text, piece) EXPECT_NE((text).find(piece), std::string::npos) << (text)

// Exit 1 from info, extract and optimize, saying every piece, no output.
void expectReadingCommandsRefuse(const fs::path& recording, const fs::path& scratch,
                                 const std::vector<std::string>& pieces) {
  for (const std::string& command :
       {"info " + quoted(recording), "extract " + quoted(recording) + " -o " + quoted(scratch / "out"),
        "optimize " + quoted(recording) + " -o " + quoted(scratch / "out")}) {
    const test::CommandResult run = hba(command);
    EXPECT_EQ(run.exit_code, 1) << command << "\n" << run.output;
    for (const std::string& piece : pieces) EXPECT_HAS(run.output, piece) << command;
    EXPECT_FALSE(fs::exists(scratch / "out")) << command;
  }
}

TEST(RecordingChecks, AFifoInARosbag2FolderIsRefusedNotWaitedFor) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 4);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 1);
  fs::remove(dir / "bag" / "run_0.db3");
  ASSERT_EQ(::mkfifo((dir / "bag" / "run_0.db3").c_str(), 0600), 0);
  expectReadingCommandsRefuse(dir / "bag", dir.path(), {"run_0.db3: is not a regular file (a FIFO)"});
}

TEST(RecordingChecks, AFifoNamedLikeARecordingIsCalledAFifo) {
  test::TempDir dir;
  for (const char* name : {"run.bag", "run.mcap", "run.db3"}) {
    ASSERT_EQ(::mkfifo((dir / name).c_str(), 0600), 0);
    const test::CommandResult run = hba("info " + quoted(dir / name));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_HAS(run.output, std::string(name) + ": is not a regular file (a FIFO)");
  }
}

TEST(RecordingChecks, AStorageFileNamedTwiceIsRefused) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 4);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 1);
  const std::string metadata = test::readText(dir / "bag" / "metadata.yaml");
  const std::string entry = "    - run_0.db3\n";
  ASSERT_NE(metadata.find(entry), std::string::npos) << metadata;
  std::string twice = metadata;
  twice.insert(twice.find(entry), entry);
  test::writeText(dir / "bag" / "metadata.yaml", twice);
  const std::string error = openError(dir / "bag");
  EXPECT_HAS(error,
             "metadata.yaml: names the storage file run_0.db3 twice (relative_file_paths entries 1 and 2");
  // Under another name for the same file.
  std::string aliased = metadata;
  aliased.insert(aliased.find(entry), "    - ./run_0.db3\n");
  test::writeText(dir / "bag" / "metadata.yaml", aliased);
  EXPECT_HAS(openError(dir / "bag"), "names the storage file run_0.db3 twice");
}

// A split folder's channel ids carry the file's index above bit 20: a topic
// id beyond that is refused by name, not read from the wrong file (found by
// reading the code behind fuzz_rosbag2_metadata).
TEST(RecordingChecks, ATopicIdTooLargeForASplitFolderIsRefused) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 4);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 2);
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const test::CommandResult renumbered =
      test::runCommand(python +
                       " -c \"import sqlite3, sys; c = sqlite3.connect(sys.argv[1]); "
                       "c.execute('UPDATE messages SET topic_id = topic_id + 1048576'); "
                       "c.execute('UPDATE topics SET id = id + 1048576'); c.commit()\" " +
                       quoted(dir / "bag" / "run_1.db3"));
  ASSERT_EQ(renumbered.exit_code, 0) << renumbered.output;
  EXPECT_HAS(openError(dir / "bag"), "run_1.db3: topic id 104857");
  EXPECT_HAS(openError(dir / "bag"), "is beyond 1048575, the largest hba reads in a split recording");
}

// A recorder killed while writing leaves its messages in run_0.db3-wal,
// indexed by run_0.db3-shm: read as they are, nothing written beside them.
TEST(RecordingChecks, ABagLeftInWalModeIsReadWithoutWritingBesideIt) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 6);
  WRITTEN_OR_SKIP(test::writeDb3(dir / "folder", dir / "bag", 1, "--wal"),
                  "node, npm or the npm registry is missing");
  ASSERT_GT(fs::file_size(dir / "bag" / "run_0.db3-wal"), 0u);
  ASSERT_TRUE(fs::exists(dir / "bag" / "run_0.db3-shm"));
  const auto before = test::fileContents(dir / "bag");
  {
    const Recording recording = Recording::open(dir / "bag");
    ASSERT_EQ(recording.size(), 6u);
    for (std::size_t k = 0; k < 6; ++k) {
      EXPECT_NEAR(recording.trajectory().stamps[k], folder.stamps[k], 1e-6);
      EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
      EXPECT_EQ(recording.loadScan(k).points, folder.scans[k].points);
    }
  }
  EXPECT_EQ(test::fileContents(dir / "bag"), before);
  // Without the index, sqlite would have to create it: refused, saying what to do.
  fs::remove(dir / "bag" / "run_0.db3-shm");
  const auto without_shm = test::fileContents(dir / "bag");
  const std::string error = openError(dir / "bag");
  EXPECT_HAS(error, "run_0.db3: the bag is still in WAL mode: run_0.db3-wal holds messages");
  EXPECT_HAS(error, "PRAGMA wal_checkpoint");
  EXPECT_EQ(test::fileContents(dir / "bag"), without_shm);
}

TEST(RecordingChecks, ANonFinitePositionIsRefusedNamingTheMessageAndField) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 6);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "nan.bag", "--bad-position '3 nan'");
  const std::string nan = openError(dir / "nan.bag");
  EXPECT_HAS(nan, "nan.bag: /Odometry message 3 at ");
  EXPECT_HAS(nan, "pose.pose.position.y is NaN");
  EXPECT_EQ(nan.find("does not match the definition"), std::string::npos) << nan;
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "inf.bag", "--bad-position '4 inf'");
  EXPECT_HAS(openError(dir / "inf.bag"), "/Odometry message 4 at ");
  EXPECT_HAS(openError(dir / "inf.bag"), "pose.pose.position.y is infinite");
  expectReadingCommandsRefuse(dir / "nan.bag", dir.path(), {"/Odometry message 3", "position.y is NaN"});
  // A text pose file refuses them too.
  test::writeText(dir / "poses.txt", "0 0 0 0 0 0 0 1\n1 nan 0 0 0 0 0 1\n");
  try {
    io::readPoses(dir / "poses.txt", io::PoseFormat::Tum);
    ADD_FAILURE() << "read a NaN position";
  } catch (const Error& e) {
    EXPECT_HAS(std::string(e.what()), "poses.txt: line 2: number 2 is NaN");
  }
}

// As a pose file's: a quaternion of norm 3 is renormalized, a (near) zero
// one refused, and neither is called a message of another definition.
TEST(RecordingChecks, AQuaternionNotOfUnitLengthIsRenormalizedAsInPoseFiles) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 5);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "three.bag", "--quaternion-scale 3");
  const Recording recording = Recording::open(dir / "three.bag");
  ASSERT_EQ(recording.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    EXPECT_LT(test::angleBetween(recording.trajectory().poses[k], folder.poses[k]), 1e-9);
    EXPECT_NEAR(recording.trajectory().poses[k].q.norm(), 1.0, 1e-12);
  }
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "zero.bag", "--quaternion-scale 0");
  const std::string zero = openError(dir / "zero.bag");
  EXPECT_HAS(zero, "/Odometry message 0 at ");
  EXPECT_HAS(zero, "pose.pose.orientation has (near) zero length (0)");
  EXPECT_EQ(zero.find("does not match the definition"), std::string::npos) << zero;
}

TEST(RecordingChecks, TwoPosesAtOneStampAreRefusedARepublishedOneIsReadOnce) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 6);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "same.bag", "--same-stamp 4");
  const std::string same = openError(dir / "same.bag");
  EXPECT_HAS(same, "same.bag: /Odometry: message 3 and message 4 share the stamp 1600000000.");
  EXPECT_HAS(same, "a trajectory has one pose at a time");
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "again.bag", "--republish 4");
  const Recording recording = Recording::open(dir / "again.bag");
  EXPECT_EQ(recording.size(), 6u);
  EXPECT_EQ(recording.recordedTrajectory().size(), 6u);
  std::string notes;
  for (const std::string& note : recording.notes()) notes += note + "\n";
  EXPECT_HAS(notes,
             "/Odometry: 1 pose repeats the stamp and pose of the one before (republished): read once");
}

TEST(RecordingChecks, StampsRunningBackwardsAreRefusedNamingTheTopicMessageAndBothStamps) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 6);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "odometry.bag", "--reverse-stamps odometry");
  const std::string odometry = openError(dir / "odometry.bag");
  EXPECT_HAS(odometry, "odometry.bag: /Odometry: the stamps run backwards at message 1: 1600000000.4");
  EXPECT_HAS(odometry, " s after 1600000000.5");
  EXPECT_HAS(odometry, "(message 0)");
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "cloud.bag", "--reverse-stamps cloud");
  const std::string cloud = openError(dir / "cloud.bag");
  EXPECT_HAS(cloud, "cloud.bag: /cloud_registered_body: the stamps run backwards at message 1: 1600000000.4");
  expectReadingCommandsRefuse(dir / "odometry.bag", dir.path(),
                              {"/Odometry: the stamps run backwards at message 1"});
  expectReadingCommandsRefuse(dir / "cloud.bag", dir.path(),
                              {"/cloud_registered_body: the stamps run backwards at message 1"});
}

// A block longer than its points is as corrupt as a shorter one (which is
// refused): half its points would be read without a word.
TEST(RecordingChecks, APointCloud2WithMoreDataThanItsPointsIsRefused) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 4);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "long.bag", "--long-cloud 2");
  const std::string error = openError(dir / "long.bag");
  const std::size_t points = folder.scans[2].size();
  EXPECT_HAS(error, "long.bag: /cloud_registered_body message 2 at ");
  EXPECT_HAS(error, "a PointCloud2 of 1 x " + std::to_string(points) + " points of 48 bytes (rows of " +
                        std::to_string(48 * points) + ") in " + std::to_string(96 * points) +
                        " bytes of data (height x row_step is " + std::to_string(48 * points) + ")");
}

TEST(RecordingChecks, TfStaticTransformsThatFormACycleAreNamed) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 4);
  // lidar in body 0.1 m ahead; body in lidar 0.5 m ahead: they contradict.
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "cycle.bag",
                    "--tf-static '0.1 0 0 0 0 0 1' --tf-static-back '0.5 0 0 0 0 0 1'");
  const std::string error = datasetError(dir / "cycle.bag");
  EXPECT_HAS(error,
             "cycle.bag: the clouds are in frame 'lidar', the poses place 'body', and /tf_static's "
             "transforms form a cycle (body in lidar, lidar in body) and contradict each other "
             "(going round moves 0.6 m");
  EXPECT_HAS(error, "--extrinsic");
  io::DatasetOverrides overrides;
  overrides.extrinsic = Pose(Quat::Identity(), Vec3(0.1, 0.0, 0.0));
  EXPECT_EQ(datasetError(dir / "cycle.bag", overrides), "");
  // A cycle whose transforms agree is still no tree.
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "agree.bag",
                    "--tf-static '0.1 0 0 0 0 0 1' --tf-static-back '-0.1 0 0 0 0 0 1'");
  const std::string agree = datasetError(dir / "agree.bag");
  EXPECT_HAS(agree, "form a cycle (body in lidar, lidar in body): a tf tree has no cycles");
}

}  // namespace
}  // namespace hba::rec
