#pragma once
// The report's read and downsample figures (thread time) are measured here,
// around the loads of a layer's clouds, by wrapping their source: scan
// sources themselves keep no clocks.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "hba/io/scan_source.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "io/spilled_scan_source.hpp"

namespace hba::pyramid {

// Thread time spent loading clouds so far, by part.
struct LoadSeconds {
  double read = 0.0;
  double downsample = 0.0;
};

// A thread-safe running total of thread time.
class ThreadSeconds {
 public:
  void add(double seconds) { nanoseconds_ += static_cast<std::int64_t>(seconds * 1e9); }
  double total() const { return static_cast<double>(nanoseconds_.load()) * 1e-9; }

 private:
  std::atomic<std::int64_t> nanoseconds_{0};
};

// Adds the thread time of every load of `inner` to `seconds`.
class TimedScanSource : public io::ScanSource {
 public:
  TimedScanSource(const io::ScanSource& inner, ThreadSeconds& seconds) : inner_(inner), seconds_(seconds) {}
  std::size_t size() const override { return inner_.size(); }
  PointCloud load(std::size_t i) const override;
  double sizeHint(std::size_t i) const override { return inner_.sizeHint(i); }

 private:
  const io::ScanSource& inner_;
  ThreadSeconds& seconds_;
};

// The clouds one layer's windows load, and what their loads took: layer-1
// scans are read and then downsampled to `voxel`; stored keyframes
// (voxel 0) are only read. With `keep`, each cloud is read (and
// downsampled) once and kept on disk for the later loads (the refinement
// and its groups read every scan again). Holds references to `clouds` and
// to itself, so it is neither copied nor moved. Throws hba::Error if `keep`
// and the temporary folder cannot be made.
class TimedClouds {
 public:
  explicit TimedClouds(const io::ScanSource& clouds, double voxel = 0.0, bool keep = false);
  TimedClouds(const TimedClouds&) = delete;
  TimedClouds& operator=(const TimedClouds&) = delete;

  const io::ScanSource& source() const { return loaded_; }
  bool kept() const { return kept_ != nullptr; }
  LoadSeconds seconds() const;

 private:
  ThreadSeconds read_seconds_, load_seconds_;
  TimedScanSource read_;                                     // `clouds`, timed
  std::optional<voxel::DownsampledScanSource> downsampled_;  // of read_, when voxel > 0
  std::unique_ptr<io::SpilledScanSource> kept_;              // of the above, when kept
  TimedScanSource loaded_;                                   // the whole load, timed
};

}  // namespace hba::pyramid
