#include "keyframe_store.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <mutex>

#include <atomic>
#include <string>
#include <system_error>

#include "hba/core/error.hpp"
#include "hba/io/kitti_bin.hpp"

namespace hba::pyramid {
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

}  // namespace

KeyframeStore::KeyframeStore(std::size_t count) : count_(count) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  const fs::path base = fs::temp_directory_path(ec);
  if (ec) throw Error("no temporary folder for keyframes: " + ec.message());
  static std::once_flag cleaned;
  std::call_once(cleaned, [&] { removeAbandonedFolders(base); });
  folder_ = base / (kPrefix + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::create_directories(folder_, ec);
  if (ec) failAt(folder_, "cannot create the keyframe folder: " + ec.message());
  remove_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(folder_);
}

KeyframeStore::~KeyframeStore() {
  remove_on_interrupt_.reset();
  std::error_code ec;
  fs::remove_all(folder_, ec);
}

fs::path KeyframeStore::pathOf(std::size_t i) const { return folder_ / (std::to_string(i) + ".bin"); }

// io's KITTI .bin files (float32 x y z intensity): exact for float points,
// no header. Written as scratch files, not atomically: they belong to this
// process, and syncing each to disk would cost more than the BA that reads
// them. Clouds without intensity come back with intensity 0, which the BA
// does not use.
void KeyframeStore::store(std::size_t i, const PointCloud& cloud) const {
  io::writeScratchKittiBin(pathOf(i), cloud);
}

PointCloud KeyframeStore::load(std::size_t i) const { return io::readKittiBin(pathOf(i)); }

}  // namespace hba::pyramid
