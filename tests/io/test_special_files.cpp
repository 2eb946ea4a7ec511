// What stands where a file should be: a FIFO, a device, a socket, a folder,
// a symbolic link loop or a dangling link is refused by every reader with a
// message naming it, before anything is opened (a FIFO would block forever).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <mutex>
#include <thread>

#include "core/input_file.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/loop_file.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/position_prior_file.hpp"
#include "hba/io/scan_file.hpp"
#include "test_dataset_support.hpp"

namespace hba::test {
namespace {
namespace fs = std::filesystem;

// Opens the FIFOs for writing every half second until destroyed: a reader
// wrongly blocked on one is released, and its test fails on the message
// instead of hanging.
class FifoRelease {
 public:
  explicit FifoRelease(std::vector<fs::path> fifos) : fifos_(std::move(fifos)), thread_([this] { run(); }) {}
  ~FifoRelease() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(500), [this] { return done_; })) {
      for (const fs::path& fifo : fifos_) {
        const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
      }
    }
  }

  std::vector<fs::path> fifos_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;  // last: starts once the rest is ready
};

void makeFifo(const fs::path& path) { ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0) << std::strerror(errno); }

const std::string kFifo = "is not a regular file (a FIFO)";

TEST(SpecialFiles, EveryReaderRefusesAFifoWithoutWaitingOnIt) {
  TempDir dir;
  const std::vector<std::string> names = {"000030.pcd", "scan.ply",  "scan.las",  "scan.bin",  "scan.xyz",
                                          "poses.txt",  "times.txt", "loops.txt", "priors.txt"};
  std::vector<fs::path> fifos;
  for (const std::string& name : names) {
    makeFifo(dir / name);
    fifos.push_back(dir / name);
  }
  const FifoRelease release(fifos);
  for (const char* scan : {"000030.pcd", "scan.ply", "scan.las", "scan.bin", "scan.xyz"}) {
    expectErrorMentioning([&] { io::readScan(dir / scan); }, {(dir / scan).string(), kFifo});
  }
  expectErrorMentioning([&] { io::readPcdHeader(dir / "000030.pcd"); }, {"000030.pcd", kFifo});
  expectErrorMentioning([&] { io::readPoses(dir / "poses.txt"); }, {"poses.txt", kFifo});
  expectErrorMentioning([&] { io::readPoses(dir / "poses.txt", io::PoseFormat::Kitti); },
                        {"poses.txt", kFifo});
  expectErrorMentioning([&] { io::readTimes(dir / "times.txt"); }, {"times.txt", kFifo});
  expectErrorMentioning([&] { io::readLoopFile(dir / "loops.txt", 10); }, {"loops.txt", kFifo});
  expectErrorMentioning([&] { io::readPositionPriorFile(dir / "priors.txt"); }, {"priors.txt", kFifo});
  expectErrorMentioning([&] { readTextFile(dir / "loops.txt"); }, {"loops.txt", kFifo});
}

TEST(SpecialFiles, ADeviceASocketAndAFolderAreNoFiles) {
  expectErrorMentioning([] { io::readPoses("/dev/null"); },
                        {"/dev/null", "is not a regular file (a character device)"});
  TempDir dir;
  fs::create_directories(dir / "folder.pcd");
  expectErrorMentioning([&] { io::readScan(dir / "folder.pcd"); }, {"folder.pcd", "is a folder, not a file"});
  expectErrorMentioning([&] { io::readPoses(dir.path()); }, {"is a folder, not a file"});

  const fs::path socket_path = dir / "poses.txt";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.string().size(), sizeof(address.sun_path));
  std::strcpy(address.sun_path, socket_path.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  expectErrorMentioning([&] { io::readPoses(socket_path); },
                        {"poses.txt", "is not a regular file (a socket)"});
  ::close(fd);
}

TEST(SpecialFiles, LinkLoopsAndDanglingLinksAreNamedSo) {
  TempDir dir;
  fs::create_symlink("b.pcd", dir / "a.pcd");
  fs::create_symlink("a.pcd", dir / "b.pcd");
  fs::create_symlink("gone.txt", dir / "poses.txt");
  expectErrorMentioning([&] { io::readScan(dir / "a.pcd"); }, {"a.pcd", "is a symbolic link loop"});
  expectErrorMentioning([&] { io::readPoses(dir / "b.pcd"); }, {"b.pcd", "is a symbolic link loop"});
  expectErrorMentioning([&] { io::readPoses(dir / "poses.txt"); },
                        {"poses.txt", "is a broken symbolic link (to gone.txt)"});
  fs::create_directory_symlink("loop_b", dir / "loop_a");
  fs::create_directory_symlink("loop_a", dir / "loop_b");
  expectErrorMentioning([&] { io::Dataset::open(dir / "loop_a"); }, {"loop_a", "is a symbolic link loop"});
  expectErrorMentioning([&] { io::Dataset::open(dir / "nowhere"); }, {"nowhere", "dataset folder not found"});
}

// Discovery names a scan that is no file at once, rather than leaving it to
// hang or fail when it is read in the middle of a run.
TEST(SpecialFiles, DiscoveryRefusesAScanThatIsNoFile) {
  TempDir dir;
  makeScans(dir / "pcd", {"0.pcd", "1.pcd", "2.pcd"});
  writeText(dir / "pose.json", hbaPoseLines(4));
  makeFifo(dir / "pcd" / "3.pcd");
  const FifoRelease release({dir / "pcd" / "3.pcd"});
  expectErrorMentioning([&] { io::Dataset::open(dir.path()); }, {"3.pcd", kFifo});
  fs::remove(dir / "pcd" / "3.pcd");
  fs::create_symlink("3.pcd", dir / "pcd" / "3.pcd");  // points to itself
  expectErrorMentioning([&] { io::Dataset::open(dir.path()); }, {"3.pcd", "is a symbolic link loop"});
  fs::remove(dir / "pcd" / "3.pcd");
  fs::create_symlink("elsewhere.pcd", dir / "pcd" / "3.pcd");
  expectErrorMentioning([&] { io::Dataset::open(dir.path()); }, {"3.pcd", "is a broken symbolic link"});
  fs::remove(dir / "pcd" / "3.pcd");
  writeText(dir / "pcd" / "3.pcd", "");
  EXPECT_EQ(io::Dataset::open(dir.path()).size(), 4u);
}

// A trajectory or times.txt under its usual name that is no file is an error,
// not passed over for another file (or for no stamps).
TEST(SpecialFiles, DiscoveryRefusesSidecarsThatAreNoFiles) {
  TempDir dir;
  makeScans(dir / "Scans", {"0.pcd", "1.pcd"});
  writeText(dir / "trajectory.txt", hbaPoseLines(2));
  makeFifo(dir / "poses.txt");
  const FifoRelease release({dir / "poses.txt", dir / "times.txt"});
  expectErrorMentioning([&] { io::Dataset::open(dir.path()); }, {"poses.txt", kFifo});
  fs::remove(dir / "poses.txt");
  EXPECT_EQ(io::Dataset::open(dir.path()).size(), 2u);
  makeFifo(dir / "times.txt");
  expectErrorMentioning([&] { io::Dataset::open(dir.path()); }, {"times.txt", kFifo});
}

// An invisible UTF-8 byte order mark, as Windows editors write it, changes
// nothing in any text format hba reads.
template <typename Read>
void expectSameWithMark(const fs::path& dir, const std::string& name, const std::string& text, Read read) {
  writeText(dir / name, text);
  const auto plain = read(dir / name);
  writeText(dir / name, "\xEF\xBB\xBF" + text);
  EXPECT_EQ(read(dir / name), plain) << name;
}

std::vector<double> flat(const Trajectory& t) {
  std::vector<double> values = t.stamps;
  for (const Pose& p : t.poses) {
    values.insert(values.end(), {p.t.x(), p.t.y(), p.t.z(), p.q.w(), p.q.x(), p.q.y(), p.q.z()});
  }
  return values;
}

TEST(ByteOrderMark, EveryTextFormatReadsAsWithout) {
  TempDir dir;
  const auto poses = [](const fs::path& p) { return flat(io::readPoses(p)); };
  expectSameWithMark(dir.path(), "kitti.txt", kittiPoseLines(3), poses);
  expectSameWithMark(dir.path(), "hba.json", hbaPoseLines(3), poses);
  expectSameWithMark(dir.path(), "tum.txt", "0.5 1 2 3 0 0 0 1\n1.5 1 2 4 0 0 0 1\n", poses);
  expectSameWithMark(dir.path(), "times.txt", "0.1\n0.2\n",
                     [](const fs::path& p) { return io::readTimes(p); });
  expectSameWithMark(dir.path(), "loops.txt", "1 7\n", [](const fs::path& p) {
    const std::vector<io::LoopRecord> loops = io::readLoopFile(p, 10);
    return std::vector<std::size_t>{loops.size(), loops.at(0).from, loops.at(0).to};
  });
  expectSameWithMark(dir.path(), "priors.txt", "0.5 1 2 3 0.1\n", [](const fs::path& p) {
    const std::vector<io::TimedPosition> priors = io::readPositionPriorFile(p);
    return std::vector<double>{priors.at(0).stamp, priors.at(0).position.x(), priors.at(0).position.z()};
  });
  const auto points = [](const fs::path& p) {
    const PointCloud cloud = io::readScan(p);
    std::vector<float> values;
    for (const Vec3f& q : cloud.points) values.insert(values.end(), {q.x(), q.y(), q.z()});
    return values;
  };
  expectSameWithMark(dir.path(), "ascii.pcd",
                     "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                     "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 2 3\n4 5 6\n",
                     points);
  expectSameWithMark(dir.path(), "ascii.ply",
                     "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n1 2 3\n4 5 6\n",
                     points);
  EXPECT_EQ(points(dir / "ascii.ply").size(), 6u);
}

// KITTI's calib.txt turns camera poses into LiDAR poses: with a mark before
// "Tr:", the same.
TEST(ByteOrderMark, KittiCalibrationReadsAsWithout) {
  TempDir dir;
  makeScans(dir / "velodyne", {"000000.bin", "000001.bin"});
  writeText(dir / "00.txt", kittiPoseLines(2));
  const std::string calib = "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: 0 -1 0 0.1 0 0 -1 0.2 1 0 0 0.3\n";
  const auto open = [&](const fs::path&) {
    const io::Dataset dataset = io::Dataset::open(dir.path());
    EXPECT_EQ(dataset.calibrationFile(), dir / "calib.txt");
    return flat(dataset.trajectory());
  };
  expectSameWithMark(dir.path(), "calib.txt", calib, open);
}

TEST(ByteOrderMark, OnlyALeadingMarkIsDropped) {
  EXPECT_EQ(withoutByteOrderMark("\xEF\xBB\xBF"
                                 "1 2"),
            "1 2");
  EXPECT_EQ(withoutByteOrderMark("1 2"), "1 2");
  EXPECT_EQ(withoutByteOrderMark("\xEF\xBB"), "\xEF\xBB");
  TempDir dir;
  writeText(dir / "poses.txt",
            "0 0 0 1 0 0 0\n\xEF\xBB\xBF"
            "1 0 0 1 0 0 0\n");
  expectErrorMentioning([&] { io::readPoses(dir / "poses.txt"); }, {"poses.txt", "line 2"});
}

}  // namespace
}  // namespace hba::test
