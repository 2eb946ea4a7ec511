#pragma once
// A scan source that reads and downsamples each scan once: the first load of
// a scan goes to the source it wraps and is kept on disk (a CloudStore in
// $TMPDIR, removed at the end); later loads read it back. A refinement of
// several blocks reads its scans several times (overlapping blocks, rigid
// groups, the re-measured self-check), and reading a kept scan costs a
// fraction of parsing and downsampling it. The clouds come back bit for bit.
#include <atomic>
#include <memory>
#include <vector>

#include "cloud_store.hpp"
#include "hba/io/scan_source.hpp"

namespace hba::io {

class SpilledScanSource : public ScanSource {
 public:
  // Throws hba::Error if the temporary folder cannot be made.
  explicit SpilledScanSource(const ScanSource& inner);
  std::size_t size() const override { return inner_.size(); }
  // Thread-safe. Throws hba::Error (a full disk).
  PointCloud load(std::size_t i) const override;
  double sizeHint(std::size_t i) const override { return inner_.sizeHint(i); }

 private:
  enum : int { kNotKept = 0, kKeeping = 1, kKept = 2 };
  const ScanSource& inner_;
  CloudStore store_;
  std::unique_ptr<std::atomic<int>[]> state_;
};

}  // namespace hba::io
