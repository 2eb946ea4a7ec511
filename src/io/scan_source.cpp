#include "hba/io/scan_source.hpp"

#include <algorithm>
#include <filesystem>
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

double DatasetScanSource::sizeHint(std::size_t i) const {
  if (dataset_.recording()) return 1.0;  // one file for all scans
  std::error_code error;
  const auto bytes = std::filesystem::file_size(dataset_.scanPath(i), error);
  return error ? 1.0 : static_cast<double>(bytes);
}

PointCloud MemoryScanSource::load(std::size_t i) const {
  if (i >= scans_.size()) outOfRange(i, scans_.size(), "scans in memory");
  return scans_[i];
}

ConcatenatedScanSource::ConcatenatedScanSource(std::vector<const ScanSource*> parts)
    : parts_(std::move(parts)), starts_{0} {
  for (const ScanSource* part : parts_) starts_.push_back(starts_.back() + part->size());
}

PointCloud ConcatenatedScanSource::load(std::size_t i) const {
  if (i >= size()) outOfRange(i, size(), "sessions");
  const std::size_t part = partOf(i);
  return parts_[part]->load(i - starts_[part]);
}

double ConcatenatedScanSource::sizeHint(std::size_t i) const {
  if (i >= size()) outOfRange(i, size(), "sessions");
  const std::size_t part = partOf(i);
  return parts_[part]->sizeHint(i - starts_[part]);
}

std::size_t ConcatenatedScanSource::partOf(std::size_t i) const {
  // The last start not after i; empty parts share a start with the next.
  const auto after = std::upper_bound(starts_.begin(), starts_.end(), i);
  return static_cast<std::size_t>(after - starts_.begin()) - 1;
}

}  // namespace hba::io
