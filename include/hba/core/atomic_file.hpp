#pragma once
// Writes a file atomically: the content goes to a temporary file beside the
// target, is flushed to disk, and only then renamed over the target. A crash
// or a kill midway leaves the old file (or none), never a half-written one.
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

namespace hba {

class RemoveOnInterrupt;

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target, bool binary = true);
  ~AtomicFile();  // removes the temporary file if commit() was not reached
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Flushes, syncs and renames into place. Throws hba::Error naming the file
  // on any failure (a full disk is reported as such).
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::ofstream out_;
  std::unique_ptr<RemoveOnInterrupt> remove_on_interrupt_;  // Ctrl-C removes the temporary
  bool committed_ = false;
};

// Convenience: writes what `fill` puts into the stream, atomically.
void writeFileAtomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& fill,
                         bool binary = true);

}  // namespace hba
