#pragma once
// Simulating and writing the scans of a sequence in parallel, one binary PCD
// a frame: shared by one sequence and each session of several.
#include <cstddef>
#include <filesystem>
#include <functional>

#include "hba/core/point_cloud.hpp"
#include "hba/sim/simulation.hpp"

namespace hba::sim {

// Creates `scans` and writes scan_frame(k) for k < frames into it, reporting
// progress as `options` asks. `scan_frame` must be thread-safe.
void writeScans(std::size_t frames, const std::function<PointCloud(std::size_t)>& scan_frame,
                const std::filesystem::path& scans, const WriteOptions& options);

}  // namespace hba::sim
