#pragma once
// Keyframe clouds of an upper layer, kept on disk (in a private temporary
// folder) instead of in memory: there are N/s^(i-1) of them on layer i, so
// held in memory they would grow with the length of the sequence. They are
// read back window by window, like layer-1 scans.
#include <cstddef>
#include <filesystem>
#include <memory>

#include "hba/core/remove_on_interrupt.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::pyramid {

class KeyframeStore : public io::ScanSource {
 public:
  // Creates the folder under the system temporary directory ($TMPDIR).
  // Throws hba::Error if it cannot.
  explicit KeyframeStore(std::size_t count);
  ~KeyframeStore() override;  // removes the folder and its files
  KeyframeStore(const KeyframeStore&) = delete;
  KeyframeStore& operator=(const KeyframeStore&) = delete;

  std::size_t size() const override { return count_; }
  const std::filesystem::path& folder() const { return folder_; }
  PointCloud load(std::size_t i) const override;
  // Thread-safe for distinct i. Throws hba::Error (e.g. a full disk).
  void store(std::size_t i, const PointCloud& cloud) const;

 private:
  std::filesystem::path pathOf(std::size_t i) const;

  std::size_t count_ = 0;
  std::filesystem::path folder_;
  std::unique_ptr<RemoveOnInterrupt> remove_on_interrupt_;  // Ctrl-C removes the folder too
};

}  // namespace hba::pyramid
