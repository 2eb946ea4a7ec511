#include "timed_clouds.hpp"

#include <algorithm>

#include "core/stopwatch.hpp"

namespace hba::pyramid {

PointCloud TimedScanSource::load(std::size_t i) const {
  const auto start = Clock::now();
  PointCloud cloud = inner_.load(i);
  seconds_.add(secondsSince(start));
  return cloud;
}

namespace {
const io::ScanSource& innermost(const io::ScanSource& read,
                                const std::optional<voxel::DownsampledScanSource>& downsampled) {
  return downsampled ? static_cast<const io::ScanSource&>(*downsampled) : read;
}
}  // namespace

TimedClouds::TimedClouds(const io::ScanSource& clouds, double voxel, bool keep)
    : read_(clouds, read_seconds_),
      downsampled_(voxel > 0.0 ? std::make_optional<voxel::DownsampledScanSource>(read_, voxel)
                               : std::nullopt),
      kept_(keep ? std::make_unique<io::SpilledScanSource>(innermost(read_, downsampled_)) : nullptr),
      loaded_(kept_ ? static_cast<const io::ScanSource&>(*kept_) : innermost(read_, downsampled_),
              load_seconds_) {}

LoadSeconds TimedClouds::seconds() const {
  const double read = read_seconds_.total();
  // A load is a read, then the downsampling: the rest of its time.
  const double downsample = downsampled_ ? std::max(0.0, load_seconds_.total() - read) : 0.0;
  return {read, downsample};
}

}  // namespace hba::pyramid
