#pragma once
// Where scans come from, for every command and module that reads them
// (merged maps, pictures, the pyramid): a count and scan i on demand, so a
// sequence need not be a folder on disk. Sources compose: a source may wrap
// another (downsampling, keeping scans on disk, timing their loads).
#include <cstddef>
#include <utility>
#include <vector>

#include "hba/core/point_cloud.hpp"

namespace hba::io {

class Dataset;

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual std::size_t size() const = 0;
  // Scan i in its sensor frame. Thread-safe. Throws hba::Error (an index
  // out of range, an unreadable scan).
  virtual PointCloud load(std::size_t i) const = 0;
  // How large scan i is, cheaply and roughly (its file's bytes, its points
  // in memory), to share work out by; 1 where a source cannot tell.
  virtual double sizeHint(std::size_t /*i*/) const { return 1.0; }
};

// The scans of a dataset, as Dataset::loadScan reads them (scans saved in
// the world frame moved back into their sensor frame). Keeps a reference:
// the dataset must outlive the source.
class DatasetScanSource : public ScanSource {
 public:
  explicit DatasetScanSource(const Dataset& dataset) : dataset_(dataset) {}
  std::size_t size() const override;
  PointCloud load(std::size_t i) const override;
  double sizeHint(std::size_t i) const override;  // the scan file's bytes

 private:
  const Dataset& dataset_;
};

// Scans held in memory (tests, generated sequences, other programs' data).
class MemoryScanSource : public ScanSource {
 public:
  explicit MemoryScanSource(std::vector<PointCloud> scans) : scans_(std::move(scans)) {}
  std::size_t size() const override { return scans_.size(); }
  PointCloud load(std::size_t i) const override;
  double sizeHint(std::size_t i) const override { return static_cast<double>(scans_.at(i).size()); }

 private:
  std::vector<PointCloud> scans_;
};

// Several sources one after the other (sessions of one place, optimized
// together): scan i of the whole is scan i - (scans before) of its part.
// Keeps references: the parts must outlive it.
class ConcatenatedScanSource : public ScanSource {
 public:
  explicit ConcatenatedScanSource(std::vector<const ScanSource*> parts);
  std::size_t size() const override { return starts_.back(); }
  PointCloud load(std::size_t i) const override;
  double sizeHint(std::size_t i) const override;
  // The index of each part's first scan in the whole, and the total at the end.
  const std::vector<std::size_t>& starts() const { return starts_; }

 private:
  std::size_t partOf(std::size_t i) const;
  std::vector<const ScanSource*> parts_;
  std::vector<std::size_t> starts_;
};

}  // namespace hba::io
