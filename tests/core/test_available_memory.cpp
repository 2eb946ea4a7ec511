#include "core/available_memory.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "hba/core/error.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

constexpr std::size_t kMiB = std::size_t{1} << 20;

// A fake root with /proc and /sys files, removed at the end.
class FakeRoot {
 public:
  FakeRoot() : path_(fs::temp_directory_path() / ("hba-fake-root-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
    ::unsetenv("HBA_MEMORY_AVAILABLE_BYTES");
  }
  ~FakeRoot() { fs::remove_all(path_); }
  FakeRoot(const FakeRoot&) = delete;
  FakeRoot& operator=(const FakeRoot&) = delete;
  void write(const std::string& file, const std::string& text) const {
    fs::create_directories((path_ / file).parent_path());
    std::ofstream(path_ / file) << text;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

const std::string kMeminfo =
    "MemTotal:       24683620 kB\nMemFree:        1000 kB\nMemAvailable:    8388608 kB\n";

TEST(AvailableMemory, IsMemAvailableWithoutACgroupLimit) {
  FakeRoot root;
  root.write("proc/meminfo", kMeminfo);
  root.write("proc/self/cgroup", "0::/\n");
  root.write("sys/fs/cgroup/memory.max", "max\n");
  const auto available = availableMemory(root.path());
  ASSERT_TRUE(available);
  EXPECT_EQ(available->bytes, 8192 * kMiB);
  EXPECT_NE(available->source.find("MemAvailable"), std::string::npos);
}

// A container of 2 GiB using 1.5 GiB, a third of it page cache: 1 GiB left
// (the cache is dropped before the kernel kills), less than MemAvailable.
TEST(AvailableMemory, IsTheRoomUnderACgroupV2LimitWhenSmaller) {
  FakeRoot root;
  root.write("proc/meminfo", kMeminfo);
  root.write("proc/self/cgroup", "0::/job/step\n");
  root.write("sys/fs/cgroup/job/step/memory.max", "max\n");
  root.write("sys/fs/cgroup/job/memory.max", std::to_string(2048 * kMiB) + "\n");
  root.write("sys/fs/cgroup/job/memory.current", std::to_string(1536 * kMiB) + "\n");
  root.write("sys/fs/cgroup/job/memory.stat", "anon 1\nfile " + std::to_string(512 * kMiB) + "\n");
  const auto available = availableMemory(root.path());
  ASSERT_TRUE(available);
  EXPECT_EQ(available->bytes, 1024 * kMiB);
  EXPECT_NE(available->source.find("cgroup"), std::string::npos);
}

TEST(AvailableMemory, IsTheRoomUnderACgroupV1Limit) {
  FakeRoot root;
  root.write("proc/meminfo", kMeminfo);
  root.write("proc/self/cgroup", "4:memory:/batch\n1:cpu:/\n");
  root.write("sys/fs/cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");  // no limit
  root.write("sys/fs/cgroup/memory/batch/memory.limit_in_bytes", std::to_string(3072 * kMiB) + "\n");
  root.write("sys/fs/cgroup/memory/batch/memory.usage_in_bytes", std::to_string(1024 * kMiB) + "\n");
  root.write("sys/fs/cgroup/memory/batch/memory.stat", "cache 5\ntotal_cache 0\n");
  const auto available = availableMemory(root.path());
  ASSERT_TRUE(available);
  EXPECT_EQ(available->bytes, 2048 * kMiB);
}

TEST(AvailableMemory, IsUnknownWithoutProc) {
  FakeRoot root;
  EXPECT_FALSE(availableMemory(root.path()));
}

TEST(AvailableMemory, TheEnvironmentFakesIt) {
  FakeRoot root;
  root.write("proc/meminfo", kMeminfo);
  ::setenv("HBA_MEMORY_AVAILABLE_BYTES", "100000000", 1);
  const auto available = availableMemory(root.path());
  ::setenv("HBA_MEMORY_AVAILABLE_BYTES", "lots", 1);
  EXPECT_THROW(availableMemory(root.path()), Error);
  ::unsetenv("HBA_MEMORY_AVAILABLE_BYTES");
  ASSERT_TRUE(available);
  EXPECT_EQ(available->bytes, 100000000u);
  EXPECT_EQ(available->source, "HBA_MEMORY_AVAILABLE_BYTES");
}

TEST(AvailableMemory, ReadsThisMachine) {
  if (!fs::exists("/proc/meminfo")) GTEST_SKIP() << "no /proc/meminfo";
  const auto available = availableMemory();
  ASSERT_TRUE(available);
  EXPECT_GT(available->bytes, 0u);
}

TEST(HumanBytes, SaysMiBOrGiB) {
  EXPECT_EQ(humanBytes(350.0 * kMiB), "350 MiB");
  EXPECT_EQ(humanBytes(1.5 * 1024 * kMiB), "1.5 GiB");
}

}  // namespace
}  // namespace hba
