#pragma once
// A scan source whose scans are those of another, voxel-downsampled
// (voxel::downsample) as they are loaded: any source, at any density.
#include <cstddef>

#include "hba/io/scan_source.hpp"

namespace hba::voxel {

class DownsampledScanSource : public io::ScanSource {
 public:
  // Keeps a reference: `inner` must outlive this source. voxel <= 0 keeps
  // every point.
  DownsampledScanSource(const io::ScanSource& inner, double voxel) : inner_(inner), voxel_(voxel) {}
  std::size_t size() const override { return inner_.size(); }
  PointCloud load(std::size_t i) const override;
  double sizeHint(std::size_t i) const override { return inner_.sizeHint(i); }

 private:
  const io::ScanSource& inner_;
  double voxel_;
};

}  // namespace hba::voxel
