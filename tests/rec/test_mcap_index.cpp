// MCAP files read as the format intends: from the summary and the chunks'
// message indexes when the file has them, by a scan of the data section
// (with a warning) when it has not, and every CRC the file gives checked.
// The files are written by npm's @mcap/core (tests/rec/write_mcap.mjs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <tuple>

#include "bag_fixture.hpp"
#include "cli_runs.hpp"
#include "hba/core/error.hpp"
#include "hba/rec/recording.hpp"
#include "rec/message_store.hpp"

namespace hba::rec {
namespace {
namespace fs = std::filesystem;

#define WRITE_MCAP_LAYOUT_OR_SKIP(folder, mcap, compression, layout)            \
  WRITTEN_OR_SKIP(::hba::test::writeMcap(folder, mcap, compression, 0, layout), \
                  "node, npm or the npm registry is missing")

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

void expectScansOf(const Recording& recording, const test::ScanFolder& folder) {
  ASSERT_LE(recording.size(), folder.scans.size());
  for (std::size_t k = 0; k < recording.size(); ++k) {
    EXPECT_NEAR(recording.trajectory().stamps[k], folder.stamps[k], 1e-6);
    EXPECT_LT((recording.trajectory().poses[k].t - folder.poses[k].t).norm(), 1e-9);
    const PointCloud scan = recording.loadScan(k);
    EXPECT_EQ(scan.points, folder.scans[k].points) << "scan " << k;
  }
}

// The bytes of scan `k`'s first point as the PointCloud2 holds them.
std::string firstPointBytes(const test::ScanFolder& folder, std::size_t k) {
  std::string bytes(12, '\0');
  std::memcpy(bytes.data(), folder.scans[k].points.front().data(), 12);
  return bytes;
}

class McapLayouts : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

// Every layout and compression reads the same scans; only a file without a
// summary is scanned, and says so.
TEST_P(McapLayouts, ReadTheSameScans) {
  const auto [compression, layout] = GetParam();
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
  WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", compression, layout);
  const Recording recording = Recording::open(dir / "run.mcap");
  ASSERT_EQ(recording.size(), 12u);
  expectScansOf(recording, folder);
  const bool scanned = layout == "no-summary";
  EXPECT_EQ(mentions(recording.warnings(), "the summary is missing: the file was written without one"),
            scanned);
  if (!scanned) {
    EXPECT_TRUE(recording.warnings().empty());
  }
}

std::string layoutName(const ::testing::TestParamInfo<McapLayouts::ParamType>& info) {
  std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param);
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(
    Files, McapLayouts,
    ::testing::Combine(::testing::Values(std::string("zstd"), std::string("lz4"), std::string("none")),
                       ::testing::Values(std::string("indexed"), std::string("no-summary"),
                                         std::string("no-message-index"))),
    layoutName);

// A recorder killed before it ended the file: no summary, no footer. The
// complete chunks are read, with a warning (hba refused such a file before).
TEST(McapIndex, AnUnfinishedRecordingIsReadWithAWarning) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 14);
  WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", "zstd", "unfinished");
  const Recording recording = Recording::open(dir / "run.mcap");
  std::size_t messages = 0;
  for (const RecordingTopic& topic : recording.topics()) messages += topic.messages;
  EXPECT_LT(messages, 28u);  // the last chunk was never written
  EXPECT_GT(recording.size(), 6u);
  expectScansOf(recording, folder);
  EXPECT_TRUE(mentions(recording.warnings(), "the summary is missing: the file ends at byte"))
      << (recording.warnings().empty() ? "" : recording.warnings().front());
}

// Opening reads the indexes only: a chunk hba cannot decompress is named
// when a message in it is read, not when the file is opened.
TEST(McapIndex, OpeningDecompressesNoChunk) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 12);
  WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", "zstd", "indexed");
  // The chunks' compression renamed, not the chunk indexes' (the summary's CRC covers them).
  test::writeText(dir / "lzma.mcap",
                  test::renamedChunkCompression(test::readText(dir / "run.mcap"), "zstd", "lzma"));
  const std::unique_ptr<MessageStore> store = openMcap(dir / "lzma.mcap");
  const std::vector<StoredMessage> clouds = store->messages("/cloud_registered_body");
  EXPECT_EQ(clouds.size(), 12u);
  EXPECT_EQ(store->messages("/Odometry").size(), 12u);
  try {
    store->read(clouds.front());
    ADD_FAILURE() << "read a chunk of unknown compression";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown chunk compression 'lzma'"), std::string::npos) << e.what();
  }
}

// A byte of a point changed inside an uncompressed chunk: the chunk's CRC
// says so, naming the file and the chunk, and hba exits 1.
TEST(McapIndex, AChangedByteInAChunkIsACrcMismatch) {
  for (const char* layout : {"indexed", "no-summary"}) {
    test::TempDir dir;
    const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
    WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", "none", layout);
    std::string bytes = test::readText(dir / "run.mcap");
    const std::size_t at = bytes.find(firstPointBytes(folder, 7));
    ASSERT_NE(at, std::string::npos);
    bytes[at] = static_cast<char>(bytes[at] ^ 0x01);
    test::writeText(dir / "damaged.mcap", bytes);
    const test::CommandResult result =
        test::runCommand(test::hbaTool() + " info " + (dir / "damaged.mcap").string());
    EXPECT_EQ(result.exit_code, 1) << layout << "\n" << result.output;
    EXPECT_NE(result.output.find((dir / "damaged.mcap").string() + ": chunk at byte "), std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find("CRC mismatch (the file is damaged)"), std::string::npos) << result.output;
  }
}

// The summary repeats the channels: a topic's name changed there is caught
// by the summary's CRC.
TEST(McapIndex, AChangedByteInTheSummaryIsACrcMismatch) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 12);
  WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", "zstd", "indexed");
  std::string bytes = test::readText(dir / "run.mcap");
  const std::size_t at = bytes.rfind("/Odometry");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 1] = 'X';
  test::writeText(dir / "damaged.mcap", bytes);
  try {
    Recording::open(dir / "damaged.mcap");
    ADD_FAILURE() << "opened a file whose summary does not match its CRC";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "damaged.mcap").string() + ": summary section (bytes "), std::string::npos)
        << message;
    EXPECT_NE(message.find("CRC mismatch (the file is damaged)"), std::string::npos) << message;
  }
}

// Without a summary the whole data section is read: its CRC is checked (a
// byte of the header record, which no other CRC covers, changed here).
TEST(McapIndex, AChangedByteOutsideChunksIsADataSectionCrcMismatch) {
  test::TempDir dir;
  test::writeScanFolder(dir / "folder", 12);
  WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", "zstd", "no-summary");
  std::string bytes = test::readText(dir / "run.mcap");
  const std::size_t at = bytes.find("hba tests");
  ASSERT_NE(at, std::string::npos);
  bytes[at] = 'H';
  test::writeText(dir / "damaged.mcap", bytes);
  try {
    Recording::open(dir / "damaged.mcap");
    ADD_FAILURE() << "opened a file whose data section does not match its CRC";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("data section (bytes 0 to "), std::string::npos) << message;
    EXPECT_NE(message.find("CRC mismatch (the file is damaged)"), std::string::npos) << message;
  }
}

// Cut inside its summary: the data section is whole, so it is scanned, with
// a warning. Cut inside the data section: refused, naming the byte, exit 1.
TEST(McapIndex, ACutFileIsScannedOrRefused) {
  test::TempDir dir;
  const test::ScanFolder folder = test::writeScanFolder(dir / "folder", 12);
  WRITE_MCAP_LAYOUT_OR_SKIP(dir / "folder", dir / "run.mcap", "lz4", "indexed");
  const std::string bytes = test::readText(dir / "run.mcap");
  test::writeText(dir / "no_footer.mcap", bytes.substr(0, bytes.size() - 100));
  const Recording recording = Recording::open(dir / "no_footer.mcap");
  EXPECT_EQ(recording.size(), 12u);
  expectScansOf(recording, folder);
  EXPECT_TRUE(mentions(recording.warnings(), "the summary is missing: the file ends at byte"));

  test::writeText(dir / "cut.mcap", bytes.substr(0, bytes.size() / 2));
  const test::CommandResult result =
      test::runCommand(test::hbaTool() + " info " + (dir / "cut.mcap").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find((dir / "cut.mcap").string() + ": truncated: a record at byte "),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace hba::rec
