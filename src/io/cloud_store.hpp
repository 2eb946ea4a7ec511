#pragma once
// Clouds kept on disk (in a private temporary folder) instead of in memory:
// an upper layer's keyframes (N/s^(i-1) of them on layer i, which held in
// memory would grow with the length of the sequence) and scans read once
// and needed again. They are read back like scans. All clouds go into one
// file, one after the other: a file a cloud cost half a millisecond each to
// create, more than reading a small scan.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/remove_on_interrupt.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::io {

class CloudStore : public ScanSource {
 public:
  // Creates the folder under the system temporary directory ($TMPDIR).
  // Throws hba::Error if it cannot.
  explicit CloudStore(std::size_t count);
  ~CloudStore() override;  // removes the folder and its files
  CloudStore(const CloudStore&) = delete;
  CloudStore& operator=(const CloudStore&) = delete;

  std::size_t size() const override { return count_; }
  const std::filesystem::path& folder() const { return folder_; }
  // Cloud i as stored (an empty cloud if it never was). Thread-safe with
  // stores of other clouds.
  PointCloud load(std::size_t i) const override;
  // Keeps `cloud` as cloud i (i < size()), replacing what was kept. Thread-
  // safe for distinct i. Throws hba::Error (e.g. a full disk).
  void store(std::size_t i, const PointCloud& cloud) const;
  // The points of cloud i as stored (0 if it never was), without reading it.
  std::size_t points(std::size_t i) const { return static_cast<std::size_t>(entries_.at(i).points); }

 private:
  // Where cloud i sits in the file: its float x y z, then its intensities.
  struct Entry {
    std::uint64_t offset = 0;
    std::uint64_t points = 0;
    bool intensity = false;
  };

  std::size_t count_ = 0;
  std::filesystem::path folder_;
  std::filesystem::path file_;
  int fd_ = -1;
  mutable std::atomic<std::uint64_t> end_{0};  // bytes handed out so far
  mutable std::vector<Entry> entries_;
  std::unique_ptr<RemoveOnInterrupt> remove_on_interrupt_;  // Ctrl-C removes the folder too
};

}  // namespace hba::io
