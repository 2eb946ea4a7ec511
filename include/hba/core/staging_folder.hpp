#pragma once
// An output folder built beside its destination and moved into place whole,
// so that a reader never sees half of it, an old run's files never sit beside
// a new run's, and an interrupted run leaves nothing visible behind.
//
// While it exists it holds a lock (`.NAME.lock` beside the destination): a
// second run into the same folder is refused instead of racing the first.
// Ctrl-C and SIGTERM remove the staging folder (RemoveOnInterrupt); a staging
// folder of a process that was killed outright is removed by the next run.
#include <filesystem>
#include <memory>

#include "hba/core/remove_on_interrupt.hpp"

namespace hba {

class StagingFolder {
 public:
  // Checks `destination` (throws hba::Error if it is a non-empty folder and
  // !force, not a folder at all, or being written by another run) and
  // creates the hidden staging folder.
  StagingFolder(std::filesystem::path destination, bool force);
  ~StagingFolder();  // removes the staging folder unless committed, releases the lock
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  const std::filesystem::path& destination() const { return destination_; }
  // Replaces the destination with the staging folder (an old destination is
  // moved aside first and deleted only once the new one is in place).
  void commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path staging_;
  std::filesystem::path lock_path_;
  int lock_fd_ = -1;
  std::unique_ptr<RemoveOnInterrupt> remove_lock_on_interrupt_, remove_on_interrupt_;
  bool committed_ = false;
};

}  // namespace hba
