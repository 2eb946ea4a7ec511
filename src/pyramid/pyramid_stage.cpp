// The paper's method (Liu et al. 2023, Sec. III): bottom-up plane BA over a
// pyramid of keyframes, top-down pose graph, repeated until the poses settle.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>

#include "bottom_up.hpp"
#include "core/stopwatch.hpp"
#include "hba/graph/pose_graph.hpp"
#include "outer_rounds.hpp"
#include "shared_outcomes.hpp"
#include "stages.hpp"
#include "top_down.hpp"
#include "upper_layer.hpp"

namespace hba::pyramid {
namespace {

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
  if (r.windows_settled > 0) {
    spdlog::info(
        "  layer {}: {} of {} windows settled (gained no more than fitting noise would) and keep their "
        "start poses",
        r.layer, r.windows_settled, r.windows);
  }
  if (r.windows_without_planes > 0) {
    spdlog::warn("  layer {}: {} of {} windows found no plane features", r.layer, r.windows_without_planes,
                 r.windows);
  }
}

// Each window of `layer` as it began and as its BA left it.
void recordWindows(const Layer& layer, const LayerOutcome& outcome, HbaReport& report) {
  for (const WindowOutcome& window : outcome.windows) {
    WindowRecord record;
    record.iteration = outcome.report.iteration;
    record.layer = outcome.report.layer;
    record.global = outcome.report.global;
    const auto first = static_cast<long>(window.window.first);
    const auto end = first + static_cast<long>(window.window.count);
    record.nodes.assign(layer.nodes.begin() + first, layer.nodes.begin() + end);
    record.start.assign(layer.poses.begin() + first, layer.poses.begin() + end);
    record.optimized = window.optimized;
    report.window_records.push_back(std::move(record));
  }
}

// The BA settings of layer `level`'s windows: the top layer's one global BA
// has its own, looser plane test; layer 1 may start finer, but never below
// the final voxel (coarsened for sparse scans: final_voxel.hpp).
ba::BaSettings windowSettings(const HbaSettings& settings, int level, bool top) {
  if (top) {
    ba::BaSettings global = settings.globalBa();
    // A top of scans (--layers 1) is the whole problem, not a view of it: a
    // real correction spread over a long sequence gains only a few times
    // fitting noise per degree of freedom there (nclt's odometry: 3.65), so
    // it never settles. A top of keyframes settles only when every window
    // below kept its start (Layer::as_input), and then gains 0.7-1.6 times
    // fitting noise at a converged map against 20-460 from a drifting one
    // (docs/pyramid.md, "Settle check").
    if (level == 1) global.significant_gain = 0.0;
    return global;
  }
  ba::BaSettings window = settings.localBa();
  if (level == 1 && settings.scan_window_voxel > 0.0)
    window.planes.voxel_size = std::max(settings.scan_window_voxel, window.final_voxel_size);
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

// The windows of layer `level`: w frames every s, or (the top) all of them.
std::vector<Window> planLayer(std::size_t frames, const HbaSettings& settings, bool top) {
  return top ? std::vector<Window>{Window{0, frames}} : planWindows(frames, settings.window, settings.stride);
}

// Bottom-up (Sec. III-B): each layer's windows optimized by plane BA, in
// parallel; their plane points, merged at the optimized relative poses,
// become the keyframes of the next layer (eq. FT), up to the top layer's
// one global BA.
struct Pyramid {
  std::vector<LayerOutcome> local;  // layers 1 .. l-1
  LayerOutcome top;                 // layer l: one window, the global BA
};

Pyramid bottomUp(Run& run, int iteration, StageTimes& times) {
  const HbaSettings& settings = run.settings;
  const int layers = run.layers;
  Pyramid pyramid;
  Layer layer = scanLayer(run.poses);
  for (int level = 1; level <= layers; ++level) {
    const bool top = level == layers;
    const auto start = Clock::now();
    const std::vector<Window> windows = planLayer(layer.poses.size(), settings, top);
    std::unique_ptr<TimedClouds> stored;
    const TimedClouds& clouds = cloudsOf(layer, run.scans, stored);
    auto keyframes = top ? nullptr : std::make_unique<io::CloudStore>(windows.size());
    const std::vector<Window> next_windows =
        top ? std::vector<Window>{} : planLayer(windows.size(), settings, level + 1 == layers);
    const std::string label = "layer " + std::to_string(level) + (top ? " (global BA)" : "");
    LayerOutcome outcome =
        optimizeLayer(layer, clouds, windows, windowSettings(settings, level, top), settings, keyframes.get(),
                      top ? 0.0 : keyframeVoxel(settings, level + 1), times, label, run.group, next_windows);
    outcome.report.iteration = iteration;
    outcome.report.layer = level;
    outcome.report.global = top;
    outcome.report.seconds = secondsSince(start);
    logLayer(outcome.report);
    if (iteration == 1 && level == 1) run.layer_one_points = outcome.report.cloud_points;
    run.planes_found += outcome.report.planes;
    run.report.layer_reports.push_back(outcome.report);
    recordWindows(layer, outcome, run.report);
    if (top) {
      pyramid.top = std::move(outcome);
    } else {
      layer = buildUpperLayer(layer, outcome, std::move(keyframes));
      pyramid.local.push_back(std::move(outcome));
    }
  }
  return pyramid;
}

// Top-down (Sec. III-C): every window's relative poses and Hessians become
// factors between layer-1 poses (eq. layer_factor), and one pose graph over
// all of them, with the closure stage's loops and priors, is solved from
// the direct assignment (the top's poses copied down the pyramid).
std::vector<Pose> topDown(Run& run, const Pyramid& pyramid, int iteration) {
  const std::vector<LayerOutcome>& local = pyramid.local;
  const LayerOutcome& top = pyramid.top;
  std::vector<Pose> assigned = directAssign(local, top.windows.front().optimized);
  IterationReport iteration_report;
  iteration_report.iteration = iteration;
  if (run.settings.top_down == TopDownMode::DirectAssign) {
    run.report.iterations.push_back(iteration_report);
    return assigned;
  }
  graph::FactorGraph graph;
  auto addWindow = [&graph](const WindowOutcome& window) {
    for (const auto& factor : window.factors) graph.add(factor);
    for (const auto& shape : window.shapes) graph.add(shape);
  };
  addWindow(top.windows.front());
  for (const auto& outcome : local) {
    for (const auto& window : outcome.windows) addWindow(window);
  }
  // The windows know nothing of the loops, and the priors set the frame.
  for (const auto& loop : run.closed.loops) graph.add(loop);
  for (const auto& prior : run.closed.priors) graph.add(prior);
  const auto start = Clock::now();
  graph::PoseGraphSettings graph_settings = run.settings.graph;
  graph_settings.threads = run.settings.threads;
  graph::PoseGraphResult solved = graph::optimizeFactorGraph(assigned, graph, graph_settings);
  iteration_report.factors = graph.size();
  iteration_report.graph_cost_before = solved.initial_cost;
  iteration_report.graph_cost_after = solved.final_cost;
  iteration_report.seconds_graph = secondsSince(start);
  run.report.seconds_graph += iteration_report.seconds_graph;
  spdlog::info("  pose graph: {} poses, {} factors, cost {:.4g} -> {:.4g}, {:.2f} s", assigned.size(),
               graph.size(), solved.initial_cost, solved.final_cost, iteration_report.seconds_graph);
  run.report.iterations.push_back(iteration_report);
  return solved.poses;
}

}  // namespace

void buildPyramid(Run& run) {
  HbaReport& report = run.report;
  OuterRounds rounds(run.settings);
  for (int iteration = 1; iteration <= run.settings.outer_iterations; ++iteration) {
    spdlog::info("iteration {}/{}: {} layers", iteration, run.settings.outer_iterations, run.layers);
    StageTimes times;
    const Pyramid pyramid = bottomUp(run, iteration, times);
    addStageTimes(times, report);
    std::vector<Pose> updated = topDown(run, pyramid, iteration);
    // The first process's pose graph speaks for all: members with other
    // thread counts (other machines) then still stop at the same iteration.
    if (run.group.size() > 1) updated = posesFromRoot(run.group, updated);
    const PoseChange u = largestChange(run.poses, updated);
    report.iterations.back().max_translation_update = u.translation_m;
    report.iterations.back().max_rotation_update = u.rotation_deg;
    spdlog::info("  largest pose update: {:.4f} m, {:.4f} deg", u.translation_m, u.rotation_deg);
    run.poses = std::move(updated);
    if (rounds.stopAfter(iteration, u)) break;
  }
  run.hierarchy = run.poses;
  report.rounds_stopped = toString(rounds.why());
  report.rounds_reason = rounds.reason();
  spdlog::info("{}", report.rounds_reason);
}

}  // namespace hba::pyramid
