#include "hba/core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "core/remove_on_interrupt.hpp"
#include "hba/core/error.hpp"

namespace hba {
namespace fs = std::filesystem;

namespace {

// Unique per process and call, so concurrent writers never share a temp file.
fs::path temporaryNameFor(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  return target.parent_path() / ("." + target.filename().string() + ".tmp." + std::to_string(::getpid()) +
                                 "." + std::to_string(counter++));
}

std::string describeErrno(int err) {
  if (err == ENOSPC) return "no space left on device (disk full)";
  if (err == EDQUOT) return "disk quota exceeded";
  return std::strerror(err);
}

// A stream only says that some write failed, and errno from that write is
// usually overwritten by the time the failure is seen. When nothing better is
// known, a file system with no space left is the cause worth naming.
int writeFailureCause(int err, const fs::path& file) {
  if (err != 0) return err;
  std::error_code ec;
  const fs::space_info space = fs::space(file.parent_path().empty() ? "." : file.parent_path(), ec);
  if (!ec && (space.available == 0 || space.free == 0)) return ENOSPC;
  return EIO;
}

void syncFile(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) failAt(path, "cannot reopen to sync: " + describeErrno(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) failAt(path, "cannot sync to disk: " + describeErrno(err));
}

}  // namespace

AtomicFile::AtomicFile(fs::path target, bool binary)
    : target_(std::move(target)), temp_(temporaryNameFor(target_)) {
  const fs::path dir = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
  if (!fs::is_directory(dir)) failAt(target_, "the output folder does not exist");
  remove_on_interrupt_ = std::make_unique<RemoveOnInterrupt>(temp_);
  errno = 0;
  out_.open(temp_,
            binary ? std::ios::out | std::ios::binary | std::ios::trunc : std::ios::out | std::ios::trunc);
  if (!out_) failAt(target_, "cannot create a file here: " + describeErrno(errno));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  errno = 0;
  out_.flush();
  const int flush_err = errno;
  out_.close();
  if (out_.fail()) {
    const int cause = writeFailureCause(flush_err, temp_);  // before removing: the disk is still full
    std::error_code ec;
    fs::remove(temp_, ec);
    failAt(target_, "write failed: " + describeErrno(cause));
  }
  syncFile(temp_);
  std::error_code ec;
  const InterruptDeferral deferral;  // an interrupt finds the temporary or the file, not both
  fs::rename(temp_, target_, ec);
  if (ec) {
    fs::remove(temp_, ec);
    failAt(target_, "cannot move the finished file into place: " + ec.message());
  }
  committed_ = true;
  remove_on_interrupt_.reset();
}

void writeFileAtomically(const fs::path& target, const std::function<void(std::ostream&)>& fill,
                         bool binary) {
  AtomicFile file(target, binary);
  fill(file.stream());
  file.commit();
}

}  // namespace hba
