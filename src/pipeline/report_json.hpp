#pragma once
// The run report as JSON (the body of report.json written by `hba optimize`).
#include <nlohmann/json.hpp>

#include <vector>

#include "hba/pipeline/hierarchical_ba.hpp"
#include "hba/pipeline/memory_estimate.hpp"
#include "hba/pipeline/window_errors.hpp"

namespace hba::pipeline {

nlohmann::json reportToJson(const HbaReport& report);

// Parts of it that the plan says too (plan.hpp).
nlohmann::json windowSizeJson(const WindowSize& windows);
nlohmann::json finalVoxelJson(const FinalVoxel& voxel);
// report.json's `memory_estimate`, without the memory found available.
nlohmann::json memoryEstimateJson(const MemoryEstimate& estimate, const ScanDensity& density);

// report.json's `window_errors`: one object per layer and round.
nlohmann::json windowErrorsToJson(const std::vector<LayerWindowErrors>& rows);

}  // namespace hba::pipeline
