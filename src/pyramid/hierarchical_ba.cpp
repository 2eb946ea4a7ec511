#include "hba/pyramid/hierarchical_ba.hpp"

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "bottom_up.hpp"
#include "closure_stage.hpp"
#include "hba/closure/closure_graph.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/core/stopwatch.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/pyramid/settings_file.hpp"
#include "hba/pyramid/window_size.hpp"
#include "outer_rounds.hpp"
#include "refine_settings.hpp"
#include "shared_outcomes.hpp"
#include "timed_clouds.hpp"
#include "top_down.hpp"
#include "upper_layer.hpp"

namespace hba::pyramid {
namespace {

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
  if (s.threads < 0) throw Error("thread count must be >= 0 (0 = as many as allowed)");
  checkSettings(s);  // the ranges of the setting table
}

void logLayer(const LayerReport& r) {
  spdlog::info("  layer {}{}: {} frames, {} windows, {} planes, plane RMS {:.4f} -> {:.4f} m, {:.2f} s",
               r.layer, r.global ? " (global BA)" : "", r.frames, r.windows, r.planes, r.rms_before,
               r.rms_after, r.seconds);
  spdlog::debug("  layer {}: {} points, {} association rounds, {} LM iterations", r.layer, r.cloud_points,
                r.association_rounds, r.lm_iterations);
  if (r.windows_untrusted > 0) {
    spdlog::warn(
        "  layer {}: {} of {} windows made the map blurrier or slid frames beyond the motion "
        "prior, and keep their input poses",
        r.layer, r.windows_untrusted, r.windows);
  }
  if (r.windows_without_planes > 0) {
    spdlog::warn("  layer {}: {} of {} windows found no plane features", r.layer, r.windows_without_planes,
                 r.windows);
  }
}

// The BA settings of the windows of layer `level` (below the top).
ba::BaSettings windowSettings(const HbaSettings& settings, int level) {
  ba::BaSettings window = settings.localBa();
  if (level == 1 && settings.scan_window_voxel > 0.0) {
    window.planes.voxel_size = settings.scan_window_voxel;
  }
  return window;
}

// `wall` split between two parts in proportion to their thread times.
std::pair<double, double> splitWall(double wall, double first, double second) {
  const double sum = first + second;
  if (!(sum > 0.0)) return {wall, 0.0};
  return {wall * first / sum, wall * second / sum};
}

void addStageTimes(const StageTimes& times, HbaReport& report) {
  const auto [read, downsample] = splitWall(times.load, times.load_parts.read, times.load_parts.downsample);
  const auto [voxelize, solve] = splitWall(times.ba, times.associate, times.solve);
  report.seconds_read += read;
  report.seconds_downsample += downsample;
  report.seconds_voxelize += voxelize;
  report.seconds_solve += solve;
  report.seconds_keyframes += times.keyframes;
}

// The clouds `layer` reads: layer 1 the scans, an upper layer its stored
// keyframes, timed in `stored` (all of their load is reading).
const TimedClouds& cloudsOf(const Layer& layer, const TimedClouds& scans,
                            std::unique_ptr<TimedClouds>& stored) {
  if (!layer.keyframes) return scans;
  stored = std::make_unique<TimedClouds>(*layer.keyframes);
  return *stored;
}

// One bottom-up pass and one top-down pass from `poses`.

std::vector<Pose> iterate(const TimedClouds& scans, const std::vector<Pose>& poses,
                          const HbaSettings& settings, const ClosureOutcome& closed, int layers,
                          int iteration, HbaReport& report, const dist::Group& group) {
  StageTimes times;
  Layer layer = scanLayer(poses);

  std::vector<LayerOutcome> local;  // layers 1 .. layers-1
  for (int level = 1; level < layers; ++level) {
    const auto start = Clock::now();
    const auto windows = planWindows(layer.poses.size(), settings.window, settings.stride);
    std::unique_ptr<TimedClouds> stored;
    const TimedClouds& clouds = cloudsOf(layer, scans, stored);
    auto keyframes = std::make_unique<io::CloudStore>(windows.size());
    // The next layer reads the keyframes: by its own windows, or all in the top one.
    const std::vector<Window> next_windows =
        level + 1 < layers ? planWindows(windows.size(), settings.window, settings.stride)
                           : std::vector<Window>{Window{0, windows.size()}};
    LayerOutcome outcome = optimizeLayer(layer, clouds, windows, windowSettings(settings, level), settings,
                                         keyframes.get(), keyframeVoxel(settings, level + 1), times,
                                         "layer " + std::to_string(level), group, next_windows);
    outcome.report.iteration = iteration;
    outcome.report.layer = level;
    outcome.report.seconds = secondsSince(start);
    logLayer(outcome.report);
    report.layer_reports.push_back(outcome.report);
    Layer upper = buildUpperLayer(layer, outcome, std::move(keyframes));
    local.push_back(std::move(outcome));
    layer = std::move(upper);
  }

  // The top layer: one global BA with its own, looser settings.
  const auto start = Clock::now();
  const std::vector<Window> all{Window{0, layer.poses.size()}};
  std::unique_ptr<TimedClouds> stored;
  const TimedClouds& top_clouds = cloudsOf(layer, scans, stored);
  LayerOutcome top = optimizeLayer(layer, top_clouds, all, settings.globalBa(), settings, nullptr, 0.0, times,
                                   "layer " + std::to_string(layers) + " (global BA)", group);
  top.report.iteration = iteration;
  top.report.layer = layers;
  top.report.global = true;
  top.report.seconds = secondsSince(start);
  logLayer(top.report);
  report.layer_reports.push_back(top.report);
  addStageTimes(times, report);

  std::vector<Pose> assigned = directAssign(local, top.windows.front().optimized);
  IterationReport iteration_report;
  iteration_report.iteration = iteration;
  if (settings.top_down == TopDownMode::DirectAssign) {
    report.iterations.push_back(iteration_report);
    return assigned;
  }

  // Top-down: a pose graph over all layer-1 poses with every window's factors,
  // started from the direct assignment (close to the answer, so LM has little to do).
  graph::FactorGraph graph;
  auto addWindow = [&graph](const WindowOutcome& window) {
    for (const auto& factor : window.factors) graph.add(factor);
    for (const auto& shape : window.shapes) graph.add(shape);
  };
  addWindow(top.windows.front());
  for (const auto& outcome : local) {
    for (const auto& window : outcome.windows) addWindow(window);
  }
  // The closure stage's loops and priors stay in: the windows know nothing
  // of the loops, and the priors set the frame.
  for (const auto& loop : closed.loops) graph.add(loop);
  for (const auto& prior : closed.priors) graph.add(prior);
  const auto graph_start = Clock::now();
  graph::PoseGraphSettings graph_settings = settings.graph;
  graph_settings.threads = settings.threads;  // resolved by runHierarchicalBa
  graph::PoseGraphResult solved = graph::optimizeFactorGraph(assigned, graph, graph_settings);
  iteration_report.factors = graph.size();
  iteration_report.graph_cost_before = solved.initial_cost;
  iteration_report.graph_cost_after = solved.final_cost;
  iteration_report.seconds_graph = secondsSince(graph_start);
  report.seconds_graph += iteration_report.seconds_graph;
  spdlog::info("  pose graph: {} poses, {} factors, cost {:.4g} -> {:.4g}, {:.2f} s", poses.size(),
               graph.size(), solved.initial_cost, solved.final_cost, iteration_report.seconds_graph);
  report.iterations.push_back(iteration_report);
  return solved.poses;
}

// The whole method, on poses near the origin.
HbaResult runNearOrigin(const TimedClouds& scans, const std::vector<Pose>& initial,
                        const HbaSettings& settings, const ClosureOutcome& closed,
                        const std::vector<std::size_t>& session_starts, const dist::Group& group) {
  const auto start = Clock::now();
  HbaResult result;
  HbaReport& report = result.report;
  report.frames = initial.size();
  report.layers = layerCount(initial.size(), settings);
  if (settings.layers > report.layers) {
    report.warnings.push_back("requested " + std::to_string(settings.layers) +
                              " layers; the sequence holds at most " + std::to_string(report.layers));
    spdlog::warn("{}", report.warnings.back());
  }

  result.poses = initial;
  if (initial.size() == 1) {
    report.warnings.push_back("a single scan: nothing to align it with, pose returned unchanged");
    spdlog::warn("{}", report.warnings.back());
    report.seconds_total = secondsSince(start);
    return result;
  }
  report.closure = closed.report;
  result.poses = closed.start;
  OuterRounds rounds(settings);
  for (int iteration = 1; iteration <= settings.outer_iterations; ++iteration) {
    spdlog::info("iteration {}/{}: {} layers", iteration, settings.outer_iterations, report.layers);
    std::vector<Pose> updated =
        iterate(scans, result.poses, settings, closed, report.layers, iteration, report, group);
    // The first process's pose graph speaks for all: members with other
    // thread counts (other machines) then still stop at the same iteration.
    if (group.size() > 1) updated = posesFromRoot(group, updated);
    const PoseChange u = largestChange(result.poses, updated);
    report.iterations.back().max_translation_update = u.translation_m;
    report.iterations.back().max_rotation_update = u.rotation_deg;
    spdlog::info("  largest pose update: {:.4f} m, {:.4f} deg", u.translation_m, u.rotation_deg);
    result.poses = std::move(updated);
    if (rounds.stopAfter(iteration, u)) break;
  }
  report.rounds_stopped = toString(rounds.why());
  report.rounds_reason = rounds.reason();
  spdlog::info("{}", report.rounds_reason);

  // What follows the hierarchy runs in the first process (the refinement
  // reads every scan), which sends the others its poses.
  if (!group.root()) {
    result.poses = posesFromRoot(group, {});
    report.seconds_total = secondsSince(start);
    return result;
  }
  // The refinement's motion prior and self-check take the closed start as
  // the input: its steps are the input's, its loops closed.
  refine::HierarchyFacts facts;
  facts.layers = report.layers;
  facts.layer_one_points = report.layer_reports.empty() ? 0 : report.layer_reports.front().cloud_points;
  facts.scans_kept = scans.kept();
  refine::RefineOutcome refined = refine::refineAndCheck(scans.source(), closed.start, result.poses, facts,
                                                         closed.priors, refineSettingsOf(settings));
  result.poses = std::move(refined.poses);
  report.consistency = std::move(refined.consistency);
  report.refinement = std::move(refined.refinement);
  report.warnings.insert(report.warnings.end(), refined.notes.warnings.begin(), refined.notes.warnings.end());
  report.seconds_voxelize += refined.notes.seconds_voxelize;
  report.seconds_solve += refined.notes.seconds_solve;
  const RefinementReport& r = report.refinement;
  if (!closed.priors.empty() && (!r.ran || (r.groups.ran && !r.groups.rejected))) {
    // The refinement's blocks hold the priors themselves; the hierarchy
    // (held at its first frame) and the groups (which do not see them) do
    // not: back onto the priors, bending only over long stretches.
    closure::ClosureGraphSettings anchoring;
    anchoring.threads = settings.threads;
    const closure::ClosureGraphResult anchored =
        closure::anchorToPriors(result.poses, closed.priors, anchoring, session_starts);
    report.closure.anchoring_move_m = largestChange(result.poses, anchored.poses).translation_m;
    report.closure.anchoring_priors_dropped =
        static_cast<std::size_t>(std::count(anchored.prior_kept.begin(), anchored.prior_kept.end(), false));
    spdlog::info("re-anchored on {} priors: poses moved up to {:.3f} m",
                 closed.priors.size() - report.closure.anchoring_priors_dropped,
                 report.closure.anchoring_move_m);
    result.poses = anchored.poses;
  }
  const PoseChange total = largestChange(initial, result.poses);
  report.largest_translation_update = total.translation_m;
  report.largest_rotation_update = total.rotation_deg;
  spdlog::info("largest pose update against the input: {:.4f} m, {:.4f} deg", total.translation_m,
               total.rotation_deg);

  std::size_t planes = 0;
  for (const auto& layer_report : report.layer_reports) planes += layer_report.planes;
  if (planes == 0) {
    report.warnings.push_back("no plane features found: poses returned unchanged");
    spdlog::warn("{}", report.warnings.back());
    result.poses = initial;
  }
  report.seconds_total = secondsSince(start) + closed.report.seconds;
  if (group.size() > 1) posesFromRoot(group, result.poses);
  return result;
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
  // Every parallel part runs on this many threads: TBB's within the arena,
  // Ceres's through the pose graph's settings.
  const WindowSize window_size = chooseWindowSize(settings, scans);
  HbaSettings resolved = withWindowSize(settings, window_size);
  resolved.threads = resolvedThreadCount(settings);
  if (window_size.automatic) {
    spdlog::info("windows of {} scans every {} (automatic: {:.0f} points a scan, {:.0f} a window at least)",
                 window_size.window, window_size.stride, window_size.points_per_scan, kWindowPoints);
  }
  tbb::task_arena arena(resolved.threads);
  // Each scan read and downsampled once: the self-check and the refinement
  // read them all again (and its groups once more).
  // Shared: the result hands the kept scans on.
  const auto layer_one =
      std::make_shared<const TimedClouds>(scans, settings.scan_voxel, /*keep=*/initial.size() > 1);
  // World points are floats: 4000 km from the origin (UTM) they are 0.25 m
  // apart. Working relative to the first pose makes the result independent of
  // where the world's origin is.
  const Vec3 origin = initial.front().t;
  const std::vector<Pose> near_initial = translated(initial, -origin);
  ClosureInputs near_closures = closures;
  for (auto& prior : near_closures.priors) prior.position -= origin;
  HbaResult result;
  Vec3 shift = Vec3::Zero();
  arena.execute([&] {
    // The closure stage in the first process, its outcome sent to the others.
    ClosureOutcome closed = group.root()
                                ? runClosureStage(layer_one->source(), near_initial, near_closures, resolved)
                                : ClosureOutcome{};
    if (group.size() > 1) shareClosures(group, closed);
    // Priors may put the start far from the input (UTM coordinates): the
    // hierarchy works near the start's first pose instead.
    shift = closed.start.front().t;
    closed.start = translated(closed.start, -shift);
    for (auto& prior : closed.priors) prior.position -= shift;
    result = runNearOrigin(*layer_one, translated(near_initial, -shift), resolved, closed,
                           closures.session_starts, group);
  });
  result.report.threads = resolved.threads;
  result.report.windows = window_size;
  result.report.processes = group.size();
  result.poses = translated(result.poses, origin + shift);
  if (layer_one->kept())
    result.scans = std::shared_ptr<const io::ScanSource>(layer_one, &layer_one->source());
  return result;
}

}  // namespace hba::pyramid
