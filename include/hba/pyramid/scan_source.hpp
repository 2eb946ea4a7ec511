#pragma once
// Where the pyramid gets layer-1 scans: read lazily (from a dataset on disk,
// or from memory in tests), already downsampled.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hba/core/point_cloud.hpp"

namespace hba::io {
class Dataset;
}

namespace hba::pyramid {

// Thread time spent inside load() so far, by part (for the report's stages).
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

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual std::size_t size() const = 0;
  // Scan i in its sensor frame, downsampled. Must be thread-safe.
  virtual PointCloud load(std::size_t i) const = 0;
  virtual LoadSeconds loadSeconds() const { return {}; }
};

// Reads scans from a dataset and downsamples them to `voxel` metres.
class DatasetScanSource : public ScanSource {
 public:
  DatasetScanSource(const io::Dataset& dataset, double voxel);
  std::size_t size() const override;
  PointCloud load(std::size_t i) const override;
  LoadSeconds loadSeconds() const override { return {read_.total(), downsample_.total()}; }

 private:
  const io::Dataset& dataset_;
  double voxel_;
  mutable ThreadSeconds read_;
  mutable ThreadSeconds downsample_;
};

// Scans held in memory (tests, small problems), downsampled to `voxel`.
class MemoryScanSource : public ScanSource {
 public:
  MemoryScanSource(std::vector<PointCloud> scans, double voxel);
  std::size_t size() const override { return scans_.size(); }
  PointCloud load(std::size_t i) const override { return scans_.at(i); }

 private:
  std::vector<PointCloud> scans_;
};

}  // namespace hba::pyramid
