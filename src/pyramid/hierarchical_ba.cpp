// The whole method as a list of stages (docs/architecture.md): closures,
// the paper's pyramid, the refinement, the anchoring on priors.
#include "hba/pyramid/hierarchical_ba.hpp"

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

#include "core/stopwatch.hpp"
#include "hba/core/error.hpp"
#include "hba/pyramid/settings_file.hpp"
#include "shared_outcomes.hpp"
#include "stages.hpp"

namespace hba::pyramid {

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

void validate(const io::ScanSource& scans, const std::vector<Pose>& initial, const HbaSettings& s,
              const ClosureInputs& closures) {
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
  if (s.threads < 0 || s.threads > kMostThreads) {
    throw Error("thread count must be from 0 (as many as allowed) to " + std::to_string(kMostThreads) +
                ", got " + std::to_string(s.threads));
  }
  checkSettings(s);  // the ranges of the setting table
}

void warn(HbaReport& report, std::string message) {
  spdlog::warn("{}", message);
  report.warnings.push_back(std::move(message));
}

// The settings the stages run with: the window size chosen (automatic:
// from the scans' density) and the thread count resolved.
HbaSettings resolve(const HbaSettings& settings, const io::ScanSource& scans, WindowSize& window_size,
                    FinalVoxel& final_voxel) {
  window_size = chooseWindowSize(settings, scans);
  const HbaSettings sized = withWindowSize(settings, window_size);
  final_voxel = chooseFinalVoxel(sized, scans);
  HbaSettings resolved = withFinalVoxel(sized, final_voxel);
  if (final_voxel.coarsened) {
    spdlog::info(
        "sparse scans ({:.1f} points of a scan in a {:g} m voxel, fewer than {:.1f}): the windows' planes "
        "end "
        "at {:g} m voxels ({:.1f} points), not {:g} m",
        final_voxel.scan_points_at_setting, final_voxel.setting, scanPointsWanted(sized), final_voxel.chosen,
        final_voxel.scan_points_at_chosen, final_voxel.setting);
  }
  resolved.threads = resolvedThreadCount(settings);
  if (window_size.automatic) {
    spdlog::info("windows of {} scans every {} (automatic: {:.0f} points a scan, {:.0f} a window at least)",
                 window_size.window, window_size.stride, window_size.points_per_scan, kWindowPoints);
  }
  return resolved;
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

// settings.threads, or (0) as many as this process allows (hba -j, a
// tbb::global_control, or the machine's cores).
int resolvedThreadCount(const HbaSettings& settings) {
  if (settings.threads > 0) return settings.threads;
  const std::size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return static_cast<int>(
      std::max<std::size_t>(1, std::min<std::size_t>(allowed, tbb::info::default_concurrency())));
}

HbaResult runHierarchicalBa(const io::ScanSource& scans, const std::vector<Pose>& initial,
                            const HbaSettings& settings, const ClosureInputs& closures,
                            const dist::Group& group) {
  validate(scans, initial, settings, closures);
  const auto start = Clock::now();
  WindowSize window_size;
  FinalVoxel final_voxel;
  const HbaSettings resolved = resolve(settings, scans, window_size, final_voxel);
  HbaResult result;
  HbaReport& report = result.report;
  report.threads = resolved.threads;
  report.windows = window_size;
  report.final_voxel = final_voxel;
  report.processes = group.size();
  report.frames = initial.size();
  report.layers = layerCount(initial.size(), resolved);
  if (settings.layers > report.layers) {
    warn(report, "requested " + std::to_string(settings.layers) + " layers; the sequence holds at most " +
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
  const auto layer_one = std::make_shared<const TimedClouds>(scans, settings.scan_voxel, /*keep=*/true);
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

}  // namespace hba::pyramid
