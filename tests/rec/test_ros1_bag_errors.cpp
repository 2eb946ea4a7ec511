// Bad recordings get a sentence naming the file and the problem, never a
// crash, and the recording is left as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "bag_fixture.hpp"
#include "hba/core/error.hpp"
#include "hba/rec/recording.hpp"

namespace hba::rec {
namespace {

using test::openError;

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

TEST(Ros1BagErrors, TwoCloudTopicsAreListedAndOneCanBeChosen) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 3);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--second-cloud-topic");
  const std::string error = openError(dir / "run.bag");
  EXPECT_NE(error.find("2 point cloud"), std::string::npos) << error;
  EXPECT_NE(error.find("--cloud-topic"), std::string::npos) << error;
  EXPECT_NE(error.find("/cloud_registered "), std::string::npos) << error;
  EXPECT_NE(error.find("/cloud_registered_body"), std::string::npos) << error;
  EXPECT_NE(error.find("3 messages"), std::string::npos) << error;
  RecordingOptions options;
  options.cloud_topic = "/cloud_registered";
  EXPECT_EQ(openError(dir / "run.bag", options), "");
  options.cloud_topic = "/Odometry";
  EXPECT_NE(openError(dir / "run.bag", options).find("is a nav_msgs/Odometry, not a point cloud"),
            std::string::npos);
  options.cloud_topic = "/points";
  EXPECT_NE(openError(dir / "run.bag", options).find("no topic /points"), std::string::npos);
}

TEST(Ros1BagErrors, NoTrajectoryOrOneThatCoversNoScan) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 3);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "none.bag", "--pose-type none");
  EXPECT_NE(openError(dir / "none.bag").find("no trajectory"), std::string::npos)
      << openError(dir / "none.bag");
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "late.bag", "--pose-shift 1000");
  const std::string late = openError(dir / "late.bag");
  EXPECT_NE(late.find("/Odometry covers none of the 3 scans"), std::string::npos) << late;
}

TEST(Ros1BagErrors, TruncatedUnknownCompressionAndMismatchedDefinitions) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 6);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--compression lz4");
  const std::string bytes = test::readText(dir / "run.bag");

  test::writeText(dir / "cut.bag", bytes.substr(0, bytes.size() * 3 / 5));
  const std::string cut = openError(dir / "cut.bag");
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
  EXPECT_NE(cut.find("cut.bag"), std::string::npos) << cut;

  std::string unknown = bytes;
  replaceAll(unknown, "compression=lz4", "compression=xz9");
  test::writeText(dir / "xz.bag", unknown);
  const std::string xz = openError(dir / "xz.bag");
  EXPECT_NE(xz.find("unknown chunk compression 'xz9'"), std::string::npos) << xz;

  WRITE_BAG_OR_SKIP(dir / "folder", dir / "mismatch.bag", "--mismatch");
  const std::string mismatch = openError(dir / "mismatch.bag");
  EXPECT_NE(mismatch.find("does not match the definition of nav_msgs/Odometry"), std::string::npos)
      << mismatch;

  test::writeText(dir / "text.bag", "not a bag at all\n");
  EXPECT_NE(openError(dir / "text.bag").find("neither a ROS 1 bag, an MCAP file nor a ROS 2 sqlite3 bag"),
            std::string::npos);
}

// Random damage anywhere in a recording: a clear error or a readable
// recording, never a crash or a runaway allocation (run under the
// sanitizers too). Returns how many of the damaged copies were refused.
int refusedDamages(const std::filesystem::path& file, const std::filesystem::path& scratch, int trials) {
  const std::string bytes = test::readText(file);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::size_t> where(0, bytes.size() - 1);
  std::uniform_int_distribution<int> value(0, 255);
  int refused = 0;
  for (int trial = 0; trial < trials; ++trial) {
    std::string damaged = bytes;
    // Damage the index and headers more often: the data bytes are only numbers.
    const std::size_t at =
        trial % 2 ? where(rng) : bytes.size() - 1 - where(rng) % std::min<std::size_t>(4096, bytes.size());
    damaged[at] = static_cast<char>(value(rng));
    test::writeText(scratch, damaged);
    if (!openError(scratch).empty()) ++refused;
  }
  return refused;
}

TEST(Ros1BagErrors, CorruptBytesNeverCrash) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 3);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "run.bag", "--compression none");
  EXPECT_GT(refusedDamages(dir / "run.bag", dir / "damaged.bag", 300), 0);
  // Livox's CustomMsg and a PointCloud2 with point times, damaged alike.
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "livox.bag", "--layout livox");
  EXPECT_GT(refusedDamages(dir / "livox.bag", dir / "damaged.bag", 200), 0);
  WRITE_BAG_OR_SKIP(dir / "folder", dir / "ouster.bag", "--layout ouster");
  EXPECT_GT(refusedDamages(dir / "ouster.bag", dir / "damaged.bag", 200), 0);
}

TEST(McapErrors, CorruptBytesNeverCrash) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 3);
  WRITE_MCAP_OR_SKIP(dir / "folder", dir / "run.mcap", "none");
  EXPECT_GT(refusedDamages(dir / "run.mcap", dir / "damaged.mcap", 300), 0);
  WRITE_MCAP_OR_SKIP(dir / "folder", dir / "zstd.mcap", "zstd");
  EXPECT_GT(refusedDamages(dir / "zstd.mcap", dir / "damaged.mcap", 300), 0);
}

TEST(Db3Errors, CorruptBytesNeverCrash) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 3);
  WRITE_DB3_OR_SKIP(dir / "folder", dir / "bag", 1);
  EXPECT_GT(refusedDamages(dir / "bag" / "run_0.db3", dir / "damaged.db3", 300), 0);
}

}  // namespace
}  // namespace hba::rec
