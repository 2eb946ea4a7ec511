// The whole method as a list of stages (docs/architecture.md): closures,
// the paper's pyramid, the refinement, the anchoring on priors.
#include "hba/pipeline/hierarchical_ba.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

#include "core/stopwatch.hpp"
#include "hba/core/error.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/settings/settings_file.hpp"
#include "shared_outcomes.hpp"
#include "stages.hpp"

namespace hba::pipeline {

void logStageTimes(Run& run);  // stage_times.cpp

namespace {

// Where a stage runs in a group of processes. The refinement runs in every
// process, each with its share of the planes; the stages after it are the
// first process's, which sends the others its poses at the end.
enum class Where { EveryProcess, FirstProcess };

struct Stage {
  const char* name;
  void (*run)(Run&);
  Where where;
};

// clang-format off
constexpr Stage kStages[] = {
    {"closures",    closeLoops,     Where::EveryProcess},
    {"pyramid",     buildPyramid,   Where::EveryProcess},
    {"refinement",  refineMap,      Where::EveryProcess},
    {"anchoring",   anchorOnPriors, Where::FirstProcess},
    {"stage times", logStageTimes,  Where::FirstProcess},
};
// clang-format on

void validate(const io::ScanSource& scans, const std::vector<Pose>& initial, const ClosureInputs& closures) {
  if (initial.size() != scans.size()) {
    throw Error("pose count (" + std::to_string(initial.size()) + ") differs from scan count (" +
                std::to_string(scans.size()) + ")");
  }
  if (initial.empty()) throw Error("no scans to optimize");
  for (const closure::LoopPair& loop : closures.loops) {
    if (loop.from >= initial.size() || loop.to >= initial.size() || loop.from == loop.to) {
      throw Error("loop closure " + std::to_string(loop.from) + " -> " + std::to_string(loop.to) +
                  " does not name two frames of the " + std::to_string(initial.size()) + " given");
    }
  }
  for (const graph::PositionPriorFactor& prior : closures.priors) {
    if (prior.node >= initial.size()) {
      throw Error("a position prior names frame " + std::to_string(prior.node) + " of " +
                  std::to_string(initial.size()));
    }
  }
}

void warn(HbaReport& report, std::string message) {
  spdlog::warn("{}", message);
  report.warnings.push_back(std::move(message));
}

// What the plan chose where the data decided it.
void logPlan(const Plan& plan) {
  const FinalVoxel& voxel = plan.final_voxel;
  if (voxel.coarsened) {
    spdlog::info(
        "sparse scans ({:.1f} points of a scan in a {:g} m voxel, fewer than {:.1f}): the windows' planes "
        "end "
        "at {:g} m voxels ({:.1f} points), not {:g} m",
        voxel.scan_points_at_setting, voxel.setting,
        scanPointsWanted(withWindowSize(plan.settings, plan.windows)), voxel.chosen,
        voxel.scan_points_at_chosen, voxel.setting);
  }
  if (plan.windows.automatic) {
    spdlog::info("windows of {} scans every {} (automatic: {:.0f} points a scan, {:.0f} a window at least)",
                 plan.windows.window, plan.windows.stride, plan.windows.points_per_scan, kWindowPoints);
  }
}

// What the first process reports once every stage ran: the final move,
// and the input back where no plane was found at all.
void finish(Run& run) {
  HbaReport& report = run.report;
  const PoseChange total = largestChange(run.input, run.poses);
  report.largest_translation_update = total.translation_m;
  report.largest_rotation_update = total.rotation_deg;
  spdlog::info("largest pose update against the input: {:.4f} m, {:.4f} deg", total.translation_m,
               total.rotation_deg);
  // A converged input is a fixed point: say so, as the reason nothing moved.
  if (total.translation_m == 0.0 && total.rotation_deg == 0.0 && run.converged_at_start) {
    spdlog::info("the input is converged: its poses are returned unchanged");
  }
  if (run.planes_found == 0) {
    warn(report, "no plane features found: poses returned unchanged");
    run.poses = run.input;
  }
}

void runStages(Run& run) {
  for (const Stage& stage : kStages) {
    if (stage.where == Where::FirstProcess && !run.group.root()) continue;
    const auto start = Clock::now();
    stage.run(run);
    run.stage_seconds.emplace_back(stage.name, secondsSince(start));
  }
  if (run.group.root()) finish(run);
  if (run.group.size() > 1) run.poses = posesFromRoot(run.group, run.poses);
}

}  // namespace

HbaResult runHierarchicalBa(const io::ScanSource& scans, const std::vector<Pose>& initial,
                            const HbaSettings& settings, const ClosureInputs& closures,
                            const dist::Group& group) {
  validate(scans, initial, closures);
  const auto start = Clock::now();
  HbaResult result = runHierarchicalBa(scans, initial, planRun(scans, settings), closures, group);
  result.report.seconds_total = secondsSince(start);  // the plan's reading included
  return result;
}

HbaResult runHierarchicalBa(const io::ScanSource& scans, const std::vector<Pose>& initial, const Plan& plan,
                            const ClosureInputs& closures, const dist::Group& group) {
  validate(scans, initial, closures);
  if (plan.frames != scans.size()) {
    throw Error("a plan of " + std::to_string(plan.frames) + " frames for " + std::to_string(scans.size()) +
                " scans: plan the run over the scans it runs on");
  }
  const auto start = Clock::now();
  logPlan(plan);
  const HbaSettings& resolved = plan.settings;
  HbaResult result;
  HbaReport& report = result.report;
  report.threads = resolved.threads;
  report.windows = plan.windows;
  report.final_voxel = plan.final_voxel;
  report.processes = group.size();
  report.frames = initial.size();
  report.layers = plan.layers;
  if (resolved.layers > report.layers) {
    warn(report, "requested " + std::to_string(resolved.layers) + " layers; the sequence holds at most " +
                     std::to_string(report.layers));
  }
  if (initial.size() == 1) {
    warn(report, "a single scan: nothing to align it with, pose returned unchanged");
    result.poses = initial;
    result.hierarchy_poses = initial;
    report.seconds_total = secondsSince(start);
    return result;
  }
  // Each scan read and downsampled once, and kept: the self-check and the
  // refinement read them all again, and the result hands them on.
  const auto layer_one =
      std::make_shared<const pyramid::TimedClouds>(scans, resolved.scan_voxel, /*keep=*/true);
  Run run(*layer_one, resolved, group);
  run.report = std::move(report);
  run.layers = run.report.layers;
  run.origin = initial.front().t;
  run.input = translated(initial, -run.origin);
  run.closures = closures;
  for (auto& prior : run.closures.priors) prior.position -= run.origin;
  // Every parallel part runs on the resolved threads: TBB's within the
  // arena, Ceres's through the pose graph's settings.
  tbb::task_arena arena(resolved.threads);
  arena.execute([&] { runStages(run); });
  result.report = std::move(run.report);
  result.report.seconds_total = secondsSince(start);
  const Vec3 back = run.origin + run.shift;
  result.poses = translated(run.poses, back);
  result.hierarchy_poses = translated(run.hierarchy, back);
  for (WindowRecord& record : result.report.window_records) {
    record.start = translated(record.start, back);
    record.optimized = translated(record.optimized, back);
  }
  if (layer_one->kept())
    result.scans = std::shared_ptr<const io::ScanSource>(layer_one, &layer_one->source());
  return result;
}

}  // namespace hba::pipeline
