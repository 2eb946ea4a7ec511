#include "hba/pipeline/plan.hpp"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <string>

#include "hba/core/error.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/settings/settings_file.hpp"
#include "report_json.hpp"

namespace hba::pipeline {

int resolvedThreadCount(const HbaSettings& settings) {
  if (settings.threads > 0) return settings.threads;
  const std::size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return static_cast<int>(
      std::max<std::size_t>(1, std::min<std::size_t>(allowed, tbb::info::default_concurrency())));
}

nlohmann::json planToJson(const Plan& plan) {
  return {{"frames", plan.frames},
          {"windows", windowSizeJson(plan.windows)},
          {"final_voxel", finalVoxelJson(plan.final_voxel)},
          {"layers", plan.layers},
          {"threads", plan.settings.threads},
          {"memory_estimate", memoryEstimateJson(plan.memory, plan.density)}};
}

Plan planRun(const io::ScanSource& scans, const HbaSettings& settings) {
  if (settings.threads < 0 || settings.threads > kMostThreads) {
    throw Error("thread count must be from 0 (as many as allowed) to " + std::to_string(kMostThreads) +
                ", got " + std::to_string(settings.threads));
  }
  settings::checkSettings(settings);  // the ranges of the setting table
  if (scans.size() == 0) throw Error("no scans to optimize");
  Plan plan;
  plan.frames = scans.size();
  // One sample of scans, read once, for the density and the final voxel.
  const ScanSample sample = readScanSample(scans, settings.scan_voxel);
  plan.density = densityOf(scans, sample, settings);
  // The scans read, as they are: hku1 in an lz4 bag weighted by its message
  // sizes came to 3 900 points a scan against 4 036 from its folder, and so
  // to other windows (39 scans against 38) and other poses.
  plan.windows = chooseWindowSize(settings, settings.window > 0 ? 0.0 : plan.density.sampled_points);
  const HbaSettings sized = withWindowSize(settings, plan.windows);
  plan.final_voxel = chooseFinalVoxel(sized, sample.clouds);
  plan.settings = withFinalVoxel(sized, plan.final_voxel);
  plan.settings.threads = resolvedThreadCount(settings);
  plan.layers = pyramid::layerCount(plan.frames, plan.settings);
  plan.memory = estimateMemory(plan.frames, plan.density, plan.settings);
  return plan;
}

}  // namespace hba::pipeline
