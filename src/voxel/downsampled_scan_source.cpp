#include "hba/voxel/downsampled_scan_source.hpp"

#include "hba/voxel/downsample.hpp"

namespace hba::voxel {

PointCloud DownsampledScanSource::load(std::size_t i) const {
  PointCloud scan = inner_.load(i);
  // Without a voxel the scan is handed on as it is, not copied.
  if (!(voxel_ > 0.0)) return scan;
  return downsample(scan, voxel_);
}

}  // namespace hba::voxel
