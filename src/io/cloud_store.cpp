#include "cloud_store.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include <atomic>
#include <string>
#include <system_error>

#include "core/temporary_folder.hpp"
#include "hba/core/error.hpp"

namespace hba::io {
namespace fs = std::filesystem;

namespace {

constexpr const char* kPrefix = "hba-keyframes-";

// A run killed midway cannot remove its folder: the next run does, once it
// sees that the process that made it is gone.
void removeAbandonedFolders(const fs::path& base) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(base, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kPrefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + std::char_traits<char>::length(kPrefix), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }
}

// All of `bytes` at `offset`, or an error naming the file.
void writeAll(int fd, const void* data, std::size_t bytes, std::uint64_t offset, const fs::path& file) {
  const char* at = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t done = ::pwrite(fd, at, bytes, static_cast<off_t>(offset));
    if (done < 0 && errno == EINTR) continue;
    if (done <= 0) failAt(file, "cannot write the kept clouds (is the disk full?)");
    at += done;
    bytes -= static_cast<std::size_t>(done);
    offset += static_cast<std::uint64_t>(done);
  }
}

void readAll(int fd, void* data, std::size_t bytes, std::uint64_t offset, const fs::path& file) {
  char* at = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t done = ::pread(fd, at, bytes, static_cast<off_t>(offset));
    if (done < 0 && errno == EINTR) continue;
    if (done <= 0) failAt(file, "cannot read the kept clouds back");
    at += done;
    bytes -= static_cast<std::size_t>(done);
    offset += static_cast<std::uint64_t>(done);
  }
}

}  // namespace

CloudStore::CloudStore(std::size_t count) : count_(count), entries_(count) {
  static std::atomic<unsigned> counter{0};
  const fs::path base = temporaryFolder();
  std::error_code ec;
  static std::once_flag cleaned;
  std::call_once(cleaned, [&] { removeAbandonedFolders(base); });
  folder_ = base / (kPrefix + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::create_directories(folder_, ec);
  if (ec) failAt(folder_, "cannot create the keyframe folder: " + ec.message());
  remove_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(folder_);
  file_ = folder_ / "clouds.bin";
  fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd_ < 0) failAt(file_, std::string("cannot create the file for kept clouds: ") + std::strerror(errno));
}

CloudStore::~CloudStore() {
  if (fd_ >= 0) ::close(fd_);
  remove_on_interrupt_.reset();
  std::error_code ec;
  fs::remove_all(folder_, ec);
}

// Scratch data, not written atomically nor synced: it belongs to this
// process, and syncing would cost more than the BA that reads it. A cloud
// stored again goes to the end of the file (its old bytes are not reused).
void CloudStore::store(std::size_t i, const PointCloud& cloud) const {
  if (i >= count_)
    throw Error("keyframe store: cloud " + std::to_string(i) + " of " + std::to_string(count_));
  Entry entry;
  entry.points = cloud.size();
  entry.intensity = cloud.hasIntensity();
  const std::size_t point_bytes = cloud.size() * sizeof(Vec3f);
  const std::size_t intensity_bytes = entry.intensity ? cloud.size() * sizeof(float) : 0;
  entry.offset = end_.fetch_add(point_bytes + intensity_bytes);
  writeAll(fd_, cloud.points.data(), point_bytes, entry.offset, file_);
  writeAll(fd_, cloud.intensity.data(), intensity_bytes, entry.offset + point_bytes, file_);
  entries_[i] = entry;
}

PointCloud CloudStore::load(std::size_t i) const {
  if (i >= count_)
    throw Error("keyframe store: cloud " + std::to_string(i) + " of " + std::to_string(count_));
  const Entry entry = entries_[i];
  PointCloud cloud;
  cloud.points.resize(entry.points);
  readAll(fd_, cloud.points.data(), entry.points * sizeof(Vec3f), entry.offset, file_);
  if (entry.intensity) {
    cloud.intensity.resize(entry.points);
    readAll(fd_, cloud.intensity.data(), entry.points * sizeof(float),
            entry.offset + entry.points * sizeof(Vec3f), file_);
  }
  return cloud;
}

}  // namespace hba::io
