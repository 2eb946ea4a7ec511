#pragma once
// A dataset folder built beside its destination and moved into place whole.
#include <filesystem>

namespace hba::sim {

class StagingFolder {
 public:
  // Checks `destination` (throws hba::Error if it is a non-empty folder and
  // !force, or not a folder at all) and creates the hidden staging folder.
  StagingFolder(std::filesystem::path destination, bool force);
  ~StagingFolder();  // removes the staging folder unless committed
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  // Replaces the destination with the staging folder (an old destination is
  // moved aside first and deleted only once the new one is in place).
  void commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace hba::sim
