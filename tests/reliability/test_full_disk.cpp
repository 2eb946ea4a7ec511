// Writing to a full disk fails with a message that says so, and leaves no
// partial file under the final name. Needs root to mount a tiny tmpfs (the
// test is skipped otherwise).
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <fstream>
#include <vector>

#include "cli_runs.hpp"
#include "synthetic_scene.hpp"
#include "test_support.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;
using test::quoted;
using test::TempDir;

// A 64 KiB tmpfs mounted for the life of the object.
class TinyDisk {
 public:
  explicit TinyDisk(const fs::path& where) : path_(where) {
    fs::create_directories(path_);
    mounted_ = ::mount("tmpfs", path_.c_str(), "tmpfs", 0, "size=64k") == 0;
  }
  ~TinyDisk() {
    if (mounted_) ::umount(path_.c_str());
  }
  TinyDisk(const TinyDisk&) = delete;
  TinyDisk& operator=(const TinyDisk&) = delete;
  bool mounted() const { return mounted_; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  bool mounted_ = false;
};

void expectDiskFullMessage(const test::CommandResult& run) {
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("no space left on device"), std::string::npos) << run.output;
}

// Nothing at all may remain: no final file and no temporary either.
void expectEmptyFolder(const fs::path& folder) {
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) ADD_FAILURE() << "left behind: " << entry.path();
  }
}

// Not even a hidden staging folder or an empty folder may remain (but
// `keep`, put there by the test).
void expectNothingLeft(const fs::path& folder, const std::string& keep = "") {
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename() != keep) ADD_FAILURE() << "left behind: " << entry.path();
  }
}

// Writes a file on the disk until no byte more fits.
void fillDisk(const fs::path& disk) {
  std::ofstream filler(disk / "filler", std::ios::binary);
  const std::string block(4096, 'x');
  for (int i = 0; i < 1024 && filler.write(block.data(), static_cast<std::streamsize>(block.size())); ++i) {
    filler.flush();
  }
}

class FullDisk : public testing::Test {
 protected:
  void SetUp() override {
    const std::vector<Pose> poses = test::straightPath(6);
    test::writeSceneDataset(tmp_ / "data", test::roomScene(3000), poses, poses);
    if (!disk_.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  }
  TempDir tmp_;
  TinyDisk disk_{tmp_ / "disk"};
};

TEST_F(FullDisk, MapTooLargeForTheDiskIsReportedAsSuch) {
  // 6 scans x 3000 points x 16 bytes: about 290 KB, far over 64 KiB.
  const test::CommandResult run =
      test::runHba("map " + quoted(tmp_ / "data") + " --voxel 0 -o " + quoted(disk_.path() / "map.pcd"));
  expectDiskFullMessage(run);
  expectEmptyFolder(disk_.path());
}

TEST_F(FullDisk, SimulateOnAFullDiskIsReportedAsSuch) {
  const test::CommandResult run = test::runHba("simulate --frames 20 -o " + quoted(disk_.path() / "sim"));
  expectDiskFullMessage(run);
  expectEmptyFolder(disk_.path());
}

TEST_F(FullDisk, AFolderOutputOnAFullDiskLeavesNoStagingBehind) {
  for (const std::string& command : std::vector<std::string>{
           "simulate --frames 20", "extract " + quoted(tmp_ / "data"), "optimize " + quoted(tmp_ / "data")}) {
    SCOPED_TRACE(command);
    const test::CommandResult run = test::runHba(command + " -o " + quoted(disk_.path() / "out"));
    expectDiskFullMessage(run);
    expectNothingLeft(disk_.path());
  }
}

// The very first write (the staging folder's marker) fails: the folder made
// for it goes too.
TEST_F(FullDisk, AnAlreadyFullDiskLeavesNoStagingBehind) {
  fillDisk(disk_.path());
  for (const std::string& command : std::vector<std::string>{
           "simulate --frames 4", "extract " + quoted(tmp_ / "data"), "optimize " + quoted(tmp_ / "data")}) {
    SCOPED_TRACE(command);
    const test::CommandResult run = test::runHba(command + " -o " + quoted(disk_.path() / "out"));
    expectDiskFullMessage(run);
    expectNothingLeft(disk_.path(), "filler");
  }
}

// Issue 57 item 8: `info` logs only debug lines, which sat in the log's
// buffer until exit, where the failed write was noticed by no one: exit 0
// with an empty log. Now every command fails, naming the log file.
TEST_F(FullDisk, ALogFileOnAFullDiskFailsEveryCommand) {
  fillDisk(disk_.path());
  const fs::path log = disk_.path() / "log.txt";
  const fs::path data = tmp_ / "data";
  for (const std::string& command :
       {"info " + quoted(data), "info --json " + quoted(data), "mme " + quoted(data),
        "map " + quoted(data) + " -o " + quoted(tmp_ / "map.pcd"),
        "eval --gt " + quoted(data / "pose.json") + " --est " + quoted(data / "pose.json")}) {
    const test::CommandResult run = test::runHba("--log-file " + quoted(log) + " " + command);
    EXPECT_EQ(run.exit_code, 1) << command << "\n" << run.output;
    EXPECT_NE(run.output.find(log.string() + ": --log-file: cannot write the log: no space left on device "
                                             "(disk full)"),
              std::string::npos)
        << command << "\n"
        << run.output;
  }
}

}  // namespace
}  // namespace hba
