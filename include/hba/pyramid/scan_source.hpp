#pragma once
// Where the pyramid gets layer-1 scans: read lazily (from a dataset on disk,
// or from memory in tests), already downsampled.
#include <cstddef>
#include <vector>

#include "hba/core/point_cloud.hpp"

namespace hba::io {
class Dataset;
}

namespace hba::pyramid {

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual std::size_t size() const = 0;
  // Scan i in its sensor frame, downsampled. Must be thread-safe.
  virtual PointCloud load(std::size_t i) const = 0;
};

// Reads scans from a dataset and downsamples them to `voxel` metres.
class DatasetScanSource : public ScanSource {
 public:
  DatasetScanSource(const io::Dataset& dataset, double voxel);
  std::size_t size() const override;
  PointCloud load(std::size_t i) const override;

 private:
  const io::Dataset& dataset_;
  double voxel_;
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
