#pragma once
// An output folder built beside its destination and moved into place whole,
// so that a reader never sees half of it, an old run's files never sit beside
// a new run's, and an interrupted run leaves nothing visible behind.
//
// While it exists it holds a lock (`.NAME.lock` beside the destination): a
// second run into the same folder is refused instead of racing the first.
// Every folder it makes carries a marker file (kOutputMarker): `force`
// replaces only a folder with that marker or an empty one, so that it can
// never delete what hba did not write. It never replaces `/`, the home
// folder, or the current folder or one that holds it.
// Ctrl-C and SIGTERM remove the staging folder (RemoveOnInterrupt); a staging
// folder of a process that was killed outright is removed by the next run.
#include <filesystem>
#include <memory>
#include <string>

#include "core/output_lock.hpp"
#include "core/remove_on_interrupt.hpp"

namespace hba {

// Throws hba::Error if `folder` is one no run may replace: `/`, the home
// folder, the current folder or a folder holding it.
void refuseProtectedFolder(const std::filesystem::path& folder);

// The file that marks a folder as written by hba (and so replaceable).
inline constexpr const char* kOutputMarker = ".hba-output";

class StagingFolder {
 public:
  // Checks `destination` (throws hba::Error if it is a non-empty folder and
  // !force, a non-empty folder without the marker, a folder no run may
  // replace, not a folder at all, or being written by another run) and
  // creates the hidden staging folder with the marker in it. `writer` names
  // the command, for the marker.
  StagingFolder(std::filesystem::path destination, bool force, const std::string& writer = "hba");
  ~StagingFolder();  // removes the staging folder unless committed, releases the lock
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  const std::filesystem::path& destination() const { return destination_; }
  // What commit() will replace: "" for nothing, else a sentence such as
  // "an earlier hba output (7 files, 1.2 MiB)", for the caller to log.
  const std::string& replaces() const { return replaces_; }
  // Replaces the destination with the staging folder (an old destination is
  // moved aside first and deleted only once the new one is in place).
  void commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path staging_;
  std::string replaces_;
  std::unique_ptr<OutputLock> lock_;
  std::unique_ptr<RemoveOnInterrupt> remove_on_interrupt_;
  bool committed_ = false;
};

}  // namespace hba
