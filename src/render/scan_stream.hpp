#pragma once
// Reading every scan once for a picture or a page (private to render):
// chunks of consecutive scans read in parallel and handed on in order, so
// that what is built from them is the same for any thread count.
#include <tbb/parallel_pipeline.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "core/progress.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/voxel/downsample.hpp"

namespace hba::render {

inline constexpr std::size_t kChunk = 25;    // consecutive scans merged together first
inline constexpr std::size_t kInFlight = 8;  // chunks read ahead of the merge: cores busy, little memory

// Reads `indices` with `read` (anything per index) in parallel, and hands
// the results to `merge` one by one in index order while later ones are
// still being read.
template <typename Part>
void streamScans(const std::vector<std::size_t>& indices, const std::function<Part(std::size_t)>& read,
                 const std::function<void(std::size_t, Part&)>& merge, Progress& progress) {
  struct Item {
    std::size_t index = 0;
    Part part;
  };
  std::size_t next = 0;
  auto source = [&](tbb::flow_control& control) -> std::size_t {
    if (next == indices.size()) {
      control.stop();
      return 0;
    }
    return indices[next++];
  };
  auto reader = [&](std::size_t i) { return std::make_shared<Item>(Item{i, read(i)}); };
  auto merger = [&](const std::shared_ptr<Item>& item) {
    merge(item->index, item->part);
    progress.advance();
  };
  tbb::parallel_pipeline(
      kInFlight,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order, source) &
          tbb::make_filter<std::size_t, std::shared_ptr<Item>>(tbb::filter_mode::parallel, reader) &
          tbb::make_filter<std::shared_ptr<Item>, void>(tbb::filter_mode::serial_in_order, merger));
}

// Scan `i` at `voxel`: downsampled here unless it came so already.
inline PointCloud loadAt(const io::ScanSource& scans, std::size_t i, double voxel, double scans_voxel) {
  return scans_voxel >= voxel ? scans.load(i) : voxel::downsample(scans.load(i), voxel);
}

// 0, 1, ..., n - 1.
inline std::vector<std::size_t> upTo(std::size_t n) {
  std::vector<std::size_t> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = i;
  return out;
}

}  // namespace hba::render
