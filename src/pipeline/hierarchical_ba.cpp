// The whole method as its stages (docs/architecture.md): closures, the
// paper's pyramid, the refinement, the anchoring on priors; the report
// assembled from what each found.
#include "hba/pipeline/hierarchical_ba.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/stopwatch.hpp"
#include "hba/core/error.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/settings/settings_file.hpp"
#include "shared_outcomes.hpp"
#include "stages.hpp"

namespace hba::pipeline {

namespace {

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
        voxel.scan_points_at_setting, voxel.setting, scanPointsWanted(plan.settings), voxel.chosen,
        voxel.scan_points_at_chosen, voxel.setting);
  }
  if (plan.windows.automatic) {
    spdlog::info("windows of {} scans every {} (automatic: {:.0f} points a scan, {:.0f} a window at least)",
                 plan.windows.window, plan.windows.stride, plan.windows.points_per_scan, kWindowPoints);
  }
}

// What each stage found, and how long each took, in the order they ran.
struct Outcomes {
  ClosedStart start;
  PyramidOutcome pyramid;
  RefinedMap refined;
  Anchoring anchored;
  std::vector<std::pair<std::string, double>> stage_seconds;
  std::vector<Pose> poses;  // the final ones, near start.shift
};

template <typename Stage>
auto timed(const char* name, Outcomes& outcomes, Stage&& stage) {
  const auto start = Clock::now();
  auto outcome = stage();
  outcomes.stage_seconds.emplace_back(name, secondsSince(start));
  return outcome;
}

// Which process runs what: the closures, the pyramid and the refinement run
// in every process of a group, each with its share (a window, a candidate,
// a plane); the anchoring and the last word on the poses are the first
// process's, which sends the others its poses at the end.
Outcomes runStages(const RunInput& in) {
  Outcomes o;
  o.start = timed("closures", o, [&] { return closeLoops(in); });
  // The refinement's first block is read, and its input's planes found,
  // beside the last pose graph (one process: a group's members find
  // planes together, in step).
  std::optional<refine::PreparedStart> prepared;
  std::function<void(std::size_t)> prepare;
  if (in.group.size() == 1) {
    prepare = [&](std::size_t layer_one_points) {
      prepared = prepareRefinement(in, o.start, layer_one_points);
    };
  }
  o.pyramid = timed("pyramid", o, [&] { return buildPyramid(in, o.start, prepare); });
  o.refined = timed("refinement", o,
                    [&] { return refineMap(in, o.start, o.pyramid, prepared ? &*prepared : nullptr); });
  o.poses = o.refined.outcome.poses;
  if (in.group.root()) {
    o.anchored = timed("anchoring", o, [&] { return anchorOnPriors(in, o.start, o.refined); });
    if (o.anchored.ran) o.poses = o.anchored.poses;
    logStageTimes(o.stage_seconds);
  }
  return o;
}

// The report's parts the stages found.
// The pyramid's records (a window's poses each: megabytes at 20 000
// frames) move into the report; finish() reads none of them.
void assembleReport(Outcomes& o, HbaReport& report) {
  report.closure = o.start.closed.report;
  report.closure.anchoring_move_m = o.anchored.move_m;
  report.closure.anchoring_priors_dropped = o.anchored.priors_dropped;
  PyramidOutcome& p = o.pyramid;
  report.layer_reports = std::move(p.layers);
  report.iterations = std::move(p.iterations);
  report.window_records = std::move(p.windows);
  report.rounds_stopped = p.rounds_stopped;
  report.rounds_reason = p.rounds_reason;
  const refine::RefineOutcome& r = o.refined.outcome;
  report.consistency = r.consistency;
  report.refinement = r.refinement;
  report.warnings.insert(report.warnings.end(), r.notes.warnings.begin(), r.notes.warnings.end());
  report.seconds_read = p.seconds_read;
  report.seconds_downsample = p.seconds_downsample;
  report.seconds_voxelize = p.seconds_voxelize + r.notes.seconds_voxelize;
  report.seconds_solve = p.seconds_solve + r.notes.seconds_solve;
  report.seconds_keyframes = p.seconds_keyframes;
  report.seconds_graph = p.seconds_graph;
}

// What the first process says once every stage ran: the final move, and
// the input back where no plane was found at all.
void finish(const Outcomes& o, std::vector<Pose>& poses, HbaReport& report) {
  const PoseChange total = largestChange(o.start.input, poses);
  report.largest_translation_update = total.translation_m;
  report.largest_rotation_update = total.rotation_deg;
  spdlog::info("largest pose update against the input: {:.4f} m, {:.4f} deg", total.translation_m,
               total.rotation_deg);
  // A converged input is a fixed point: say so, as the reason nothing moved.
  if (total.translation_m == 0.0 && total.rotation_deg == 0.0 &&
      o.refined.outcome.refinement.converged_at_start) {
    spdlog::info("the input is converged: its poses are returned unchanged");
  }
  if (o.pyramid.planes_found == 0) {
    warn(report, "no plane features found: poses returned unchanged");
    poses = o.start.input;
  }
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
  RunInput in(*layer_one, resolved, group);
  in.layers = report.layers;
  const Vec3 origin = initial.front().t;
  in.input = translated(initial, -origin);
  in.closures = closures;
  for (auto& prior : in.closures.priors) prior.position -= origin;
  // Every parallel part runs on the resolved threads: TBB's within the
  // arena, Ceres's through the pose graph's settings.
  tbb::task_arena arena(resolved.threads);
  Outcomes outcomes;
  arena.execute([&] { outcomes = runStages(in); });
  assembleReport(outcomes, report);
  std::vector<Pose> poses = std::move(outcomes.poses);
  if (group.root()) finish(outcomes, poses, report);
  if (group.size() > 1) poses = posesFromRoot(group, poses);
  report.seconds_total = secondsSince(start);
  const Vec3 back = origin + outcomes.start.shift;
  result.poses = translated(poses, back);
  result.hierarchy_poses = translated(outcomes.pyramid.poses, back);
  for (WindowRecord& record : report.window_records) {
    record.start = translated(record.start, back);
    record.optimized = translated(record.optimized, back);
  }
  if (layer_one->kept())
    result.scans = std::shared_ptr<const io::ScanSource>(layer_one, &layer_one->source());
  return result;
}

}  // namespace hba::pipeline
