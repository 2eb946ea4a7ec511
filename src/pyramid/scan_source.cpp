#include "hba/pyramid/scan_source.hpp"

#include "hba/io/dataset.hpp"
#include "hba/voxel/downsample.hpp"
#include "hba/core/stopwatch.hpp"

namespace hba::pyramid {

DatasetScanSource::DatasetScanSource(const io::Dataset& dataset, double voxel)
    : dataset_(dataset), voxel_(voxel) {}

std::size_t DatasetScanSource::size() const { return dataset_.size(); }

PointCloud DatasetScanSource::load(std::size_t i) const {
  const auto start = Clock::now();
  const PointCloud scan = dataset_.loadScan(i);
  const auto read = Clock::now();
  PointCloud kept = voxel::downsample(scan, voxel_);
  read_.add(secondsBetween(start, read));
  downsample_.add(secondsSince(read));
  return kept;
}

MemoryScanSource::MemoryScanSource(std::vector<PointCloud> scans, double voxel)
    : scans_(std::move(scans)) {
  for (auto& scan : scans_) scan = voxel::downsample(scan, voxel);
}

}  // namespace hba::pyramid
