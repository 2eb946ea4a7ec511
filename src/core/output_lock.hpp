#pragma once
// A claim on an output (a file or a folder) for as long as a run writes it:
// an exclusive lock on `.NAME.lock` beside it, so that a second run into the
// same output is refused instead of silently replacing the first one's work.
#include <filesystem>
#include <memory>

#include "core/remove_on_interrupt.hpp"

namespace hba {

class OutputLock {
 public:
  // Throws hba::Error naming `output` if another process holds the lock.
  // The parent folder must exist.
  explicit OutputLock(const std::filesystem::path& output);
  ~OutputLock();  // removes the lock file while still holding it, then releases it
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::filesystem::path lock_path_;
  int fd_ = -1;
  std::unique_ptr<RemoveOnInterrupt> remove_on_interrupt_;
};

}  // namespace hba
