#include "hba/pipeline/deskew_passes.hpp"

#include <spdlog/spdlog.h>

#include "hba/core/error.hpp"

namespace hba::pipeline {

DatasetRun runWithDeskewPasses(io::Dataset& dataset, const io::ScanSource& scans,
                               const std::vector<Pose>& input, const Plan& plan,
                               const pipeline::ClosureInputs& closures, int passes,
                               const dist::Group& group) {
  if (passes < 1) throw ValueError("deskew passes: " + std::to_string(passes) + " (at least 1)");
  DatasetRun run;
  run.result = pipeline::runHierarchicalBa(scans, input, plan, closures, group);
  double seconds_before = 0.0;  // of the earlier passes
  for (int pass = 2; dataset.pointTimes() && pass <= passes; ++pass) {
    pipeline::HbaReport& report = run.result.report;
    run.earlier_passes.push_back({report.largest_translation_update, report.seconds_total - seconds_before});
    seconds_before = report.seconds_total;
    spdlog::info("raw sweeps: pass {} of {}, deskewed by the poses of pass {}", pass, passes, pass - 1);
    dataset.deskewBy(run.result.poses);
    run.result = pipeline::runHierarchicalBa(scans, run.result.poses, plan, closures, group);
    // The report speaks of the whole run: against the input, in all passes' time.
    const PoseChange total = largestChange(input, run.result.poses);
    run.result.report.largest_translation_update = total.translation_m;
    run.result.report.largest_rotation_update = total.rotation_deg;
    run.result.report.seconds_total += seconds_before;
    spdlog::info("largest pose update against the input over {} passes: {:.4f} m, {:.4f} deg", pass,
                 total.translation_m, total.rotation_deg);
  }
  return run;
}

nlohmann::json deskewReport(const io::Dataset& dataset, const DatasetRun& run) {
  if (!dataset.pointTimes()) return nullptr;
  nlohmann::json earlier = nlohmann::json::array();
  for (const DeskewPass& pass : run.earlier_passes) {
    earlier.push_back(
        {{"largest_update_against_input_m", pass.largest_update_against_input_m}, {"seconds", pass.seconds}});
  }
  return {{"point_times", dataset.pointTimes()->describe()},
          {"passes", run.earlier_passes.size() + 1},
          {"earlier_passes", earlier}};
}

}  // namespace hba::pipeline
