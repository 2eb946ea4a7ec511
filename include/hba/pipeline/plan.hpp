#pragma once
// What a run of the method will do, worked out once from the settings and
// the data before any stage starts: the layer-1 windows (automatic: from the
// scans' density), where the windows' association ends, the pyramid's
// layers, the threads, and the memory all that needs. The run, the memory
// check and the report all take it from here, by value.
#include <cstddef>

#include <nlohmann/json.hpp>

#include "hba/io/scan_source.hpp"
#include "hba/pipeline/final_voxel.hpp"
#include "hba/pipeline/memory_estimate.hpp"
#include "hba/pipeline/window_size.hpp"
#include "hba/settings/settings.hpp"

namespace hba::pipeline {

struct Plan {
  std::size_t frames = 0;
  ScanDensity density;     // from a few scans read (memory_estimate.hpp)
  WindowSize windows;      // the layer-1 windows (window_size.hpp)
  FinalVoxel final_voxel;  // where the windows' association ends (final_voxel.hpp)
  int layers = 0;          // of the pyramid, its top included
  // As given, with the window, stride, final voxels and threads above
  // filled in: what every stage runs with.
  HbaSettings settings;
  MemoryEstimate memory;  // of this run
};

// The plan of a run of `settings` over `scans` (as given: sensor frame, full
// density; a few of them are read). Throws hba::Error where a setting is
// out of its range or the thread count is.
Plan planRun(const io::ScanSource& scans, const HbaSettings& settings);

// The plan as `hba optimize --print-plan` and `hba.plan` give it: frames,
// windows, final_voxel, layers and threads as report.json says them, and
// the memory estimate (report.json's memory_estimate, without the memory
// available).
nlohmann::json planToJson(const Plan& plan);

// The threads a run of `settings` uses: settings.threads, or (0) as many as
// this process allows (hba -j, a tbb::global_control, or the machine's cores).
int resolvedThreadCount(const HbaSettings& settings);

}  // namespace hba::pipeline
