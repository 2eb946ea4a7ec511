#include "hba/pyramid/scan_source.hpp"

#include "hba/io/dataset.hpp"
#include "hba/voxel/downsample.hpp"

namespace hba::pyramid {

DatasetScanSource::DatasetScanSource(const io::Dataset& dataset, double voxel)
    : dataset_(dataset), voxel_(voxel) {}

std::size_t DatasetScanSource::size() const { return dataset_.size(); }

PointCloud DatasetScanSource::load(std::size_t i) const {
  return voxel::downsample(dataset_.loadScan(i), voxel_);
}

MemoryScanSource::MemoryScanSource(std::vector<PointCloud> scans, double voxel)
    : scans_(std::move(scans)) {
  for (auto& scan : scans_) scan = voxel::downsample(scan, voxel);
}

}  // namespace hba::pyramid
