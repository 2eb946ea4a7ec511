#include "hba/io/scan_source.hpp"

#include <string>

#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"

namespace hba::io {
namespace {

[[noreturn]] void outOfRange(std::size_t i, std::size_t size, const std::string& source) {
  throw Error(source + ": scan " + std::to_string(i) + " asked for, but there are " + std::to_string(size) +
              " scans");
}

}  // namespace

std::size_t DatasetScanSource::size() const { return dataset_.size(); }

PointCloud DatasetScanSource::load(std::size_t i) const {
  if (i >= dataset_.size()) outOfRange(i, dataset_.size(), dataset_.root().string());
  return dataset_.loadScan(i);
}

PointCloud MemoryScanSource::load(std::size_t i) const {
  if (i >= scans_.size()) outOfRange(i, scans_.size(), "scans in memory");
  return scans_[i];
}

}  // namespace hba::io
