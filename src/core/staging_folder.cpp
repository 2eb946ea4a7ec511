#include "hba/core/staging_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "hba/core/error.hpp"

namespace hba {
namespace fs = std::filesystem;

namespace {

fs::path besideWithSuffix(const fs::path& destination, const std::string& suffix) {
  return destination.parent_path() /
         ("." + destination.filename().string() + suffix + std::to_string(::getpid()));
}

// Staging folders (".NAME.partial-PID") of processes that no longer exist:
// killed outright (SIGKILL, power loss), they could not clean up.
void removeAbandonedStaging(const fs::path& destination) {
  const std::string prefix = "." + destination.filename().string() + ".partial-";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(destination.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove_all(entry.path(), ignored);
    }
  }
}

// An exclusive lock on `path` for as long as the returned descriptor is
// open, or -1 if another process holds it. A lock file unlinked by its last
// holder between our open and our lock is retried, so two runs never both
// believe they own the folder.
int lockFile(const fs::path& path) {
  for (int attempt = 0; attempt < 10; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) failAt(path, std::string("cannot create the lock file: ") + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd);
      return -1;
    }
    struct stat held {
    }, current{};
    if (::fstat(fd, &held) == 0 && ::stat(path.c_str(), &current) == 0 && held.st_ino == current.st_ino) {
      return fd;
    }
    ::close(fd);
  }
  failAt(path, "cannot lock the output folder");
}

}  // namespace

StagingFolder::StagingFolder(fs::path destination, bool force)
    : destination_(fs::absolute(std::move(destination)).lexically_normal()) {
  if (destination_.filename().empty()) destination_ = destination_.parent_path();
  std::error_code ec;
  if (fs::exists(destination_, ec)) {
    if (!fs::is_directory(destination_, ec)) failAt(destination_, "exists and is not a folder");
    if (!force && !fs::is_empty(destination_, ec)) {
      failAt(destination_, "the output folder is not empty (use --force to replace it)");
    }
  }
  // Like mkdir -p: `-o results/run1` creates results/ too.
  fs::create_directories(destination_.parent_path(), ec);
  if (!fs::is_directory(destination_.parent_path(), ec)) {
    failAt(destination_, "cannot create the parent folder" + (ec ? ": " + ec.message() : std::string()));
  }
  lock_path_ = destination_.parent_path() / ("." + destination_.filename().string() + ".lock");
  lock_fd_ = lockFile(lock_path_);
  if (lock_fd_ < 0) {
    failAt(destination_, "another hba run is writing this folder; wait for it to finish or choose another");
  }
  remove_lock_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(lock_path_);
  removeAbandonedStaging(destination_);
  staging_ = besideWithSuffix(destination_, ".partial-");
  remove_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(staging_);
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec) {
    failAt(staging_, "cannot create the staging folder: " + ec.message());
  }
}

StagingFolder::~StagingFolder() {
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
  remove_on_interrupt_.reset();
  remove_lock_on_interrupt_.reset();
  if (lock_fd_ >= 0) {
    fs::remove(lock_path_, ec);  // while still holding it (see lockFile)
    ::close(lock_fd_);
  }
}

void StagingFolder::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(destination_, ec)) {
    old = besideWithSuffix(destination_, ".old-");
    fs::remove_all(old, ec);
    fs::rename(destination_, old, ec);
    if (ec) failAt(destination_, "cannot move the old output folder aside: " + ec.message());
  }
  fs::rename(staging_, destination_, ec);
  if (ec) {
    std::error_code restore_ec;
    if (!old.empty()) fs::rename(old, destination_, restore_ec);
    failAt(destination_, "cannot move the finished dataset into place: " + ec.message());
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace hba
