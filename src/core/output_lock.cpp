#include "core/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "hba/core/error.hpp"

namespace hba {
namespace fs = std::filesystem;

namespace {

// An exclusive lock on `path` for as long as the returned descriptor is
// open, or -1 if another process holds it. A lock file unlinked by its last
// holder between our open and our lock is retried, so two runs never both
// believe they own the output.
int lockFile(const fs::path& path) {
  for (int attempt = 0; attempt < 10; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) failAt(path, std::string("cannot create the lock file: ") + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd);
      return -1;
    }
    struct stat held = {};
    struct stat current = {};
    if (::fstat(fd, &held) == 0 && ::stat(path.c_str(), &current) == 0 && held.st_ino == current.st_ino) {
      return fd;
    }
    ::close(fd);
  }
  failAt(path, "cannot lock the output");
}

}  // namespace

OutputLock::OutputLock(const fs::path& output) {
  const fs::path absolute = fs::absolute(output).lexically_normal();
  const fs::path target = absolute.filename().empty() ? absolute.parent_path() : absolute;
  lock_path_ = target.parent_path() / ("." + target.filename().string() + ".lock");
  interruptPointForTests("output-locking");
  // Registered before the file is made, both under a deferral: an interrupt
  // in between waits, then finds the file registered and removes it.
  const InterruptDeferral defer;
  remove_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(lock_path_);
  fd_ = lockFile(lock_path_);
  if (fd_ < 0) {
    remove_on_interrupt_.reset();  // another run's lock: never ours to remove
    failAt(target, "another hba run is writing this output; wait for it to finish or choose another");
  }
}

OutputLock::~OutputLock() {
  remove_on_interrupt_.reset();
  std::error_code ec;
  fs::remove(lock_path_, ec);  // while still holding it (see lockFile)
  ::close(fd_);
}

}  // namespace hba
