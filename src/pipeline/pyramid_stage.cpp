// The pyramid stage: the paper's method (src/pyramid/pyramid.hpp), bottom-up
// and top-down, repeated until the poses settle; each layer and pose graph
// timed, logged and reported, the pose graph's poses shared by a group.
#include <spdlog/spdlog.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/stopwatch.hpp"
#include "hba/graph/pose_graph.hpp"
#include "outer_rounds.hpp"
#include "pyramid/pyramid.hpp"
#include "shared_outcomes.hpp"
#include "stages.hpp"

namespace hba::pipeline {
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
  if (r.windows_solved_again > 0) {
    spdlog::debug(
        "  layer {}: {} windows failed the trust check and were solved again on their input's planes",
        r.layer, r.windows_solved_again);
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
void recordWindows(const pyramid::Layer& layer, const pyramid::LayerOutcome& outcome,
                   std::vector<WindowRecord>& records) {
  for (const pyramid::WindowOutcome& window : outcome.windows) {
    WindowRecord record;
    record.iteration = outcome.report.iteration;
    record.layer = outcome.report.layer;
    record.global = outcome.report.global;
    const auto first = static_cast<long>(window.window.first);
    const auto end = first + static_cast<long>(window.window.count);
    record.nodes.assign(layer.nodes.begin() + first, layer.nodes.begin() + end);
    record.start.assign(layer.poses.begin() + first, layer.poses.begin() + end);
    record.optimized = window.optimized;
    records.push_back(std::move(record));
  }
}

// `wall` split between two parts in proportion to their thread times.
std::pair<double, double> splitWall(double wall, double first, double second) {
  const double sum = first + second;
  if (!(sum > 0.0)) return {wall, 0.0};
  return {wall * first / sum, wall * second / sum};
}

void addStageTimes(const pyramid::StageTimes& times, PyramidOutcome& report) {
  const auto [read, downsample] = splitWall(times.load, times.load_parts.read, times.load_parts.downsample);
  const auto [voxelize, solve] = splitWall(times.ba, times.associate, times.solve);
  report.seconds_read += read;
  report.seconds_downsample += downsample;
  report.seconds_voxelize += voxelize;
  report.seconds_solve += solve;
  report.seconds_keyframes += times.keyframes;
}

// The bottom-up pass from `out.poses`, each layer logged and reported as it
// ends.
pyramid::Pyramid bottomUp(const RunInput& in, int iteration, pyramid::StageTimes& times,
                          PyramidOutcome& out) {
  pyramid::LayerWatch watch{in.group};
  auto layer_start = Clock::now();
  watch.layer_done = [&](int level, const pyramid::Layer& layer, pyramid::LayerOutcome& outcome) {
    outcome.report.iteration = iteration;
    outcome.report.layer = level;
    outcome.report.global = level == in.layers;
    outcome.report.seconds = secondsSince(layer_start);
    logLayer(outcome.report);
    if (iteration == 1 && level == 1) out.layer_one_points = outcome.report.cloud_points;
    out.planes_found += outcome.report.planes;
    out.layers.push_back(outcome.report);
    recordWindows(layer, outcome, out.windows);
    layer_start = Clock::now();
  };
  pyramid::Pyramid built = pyramid::bottomUp(in.scans, out.poses, in.layers, in.settings, watch);
  times = watch.times;
  return built;
}

// The top-down pass, with the closure stage's loops and priors, reported.
std::vector<Pose> topDown(const RunInput& in, const ClosedStart& start, const pyramid::Pyramid& built,
                          int iteration, PyramidOutcome& out) {
  const auto began = Clock::now();
  const pyramid::TopDown down = pyramid::topDown(built, start.closed.loops, start.closed.priors, in.settings);
  IterationReport iteration_report;
  iteration_report.iteration = iteration;
  if (down.factors > 0) {
    iteration_report.factors = down.factors;
    iteration_report.graph_cost_before = down.cost_before;
    iteration_report.graph_cost_after = down.cost_after;
    iteration_report.seconds_graph = secondsSince(began);
    out.seconds_graph += iteration_report.seconds_graph;
    spdlog::info("  pose graph: {} poses, {} factors, cost {:.4g} -> {:.4g}, {:.2f} s", down.poses.size(),
                 down.factors, down.cost_before, down.cost_after, iteration_report.seconds_graph);
  }
  out.iterations.push_back(iteration_report);
  return down.poses;
}

}  // namespace

PyramidOutcome buildPyramid(const RunInput& in, const ClosedStart& start,
                            const std::function<void(std::size_t layer_one_points)>& beside_last_graph) {
  PyramidOutcome out;
  out.poses = start.closed.start;
  OuterRounds rounds(in.settings);
  for (int iteration = 1; iteration <= in.settings.outer_iterations; ++iteration) {
    spdlog::info("iteration {}/{}: {} layers", iteration, in.settings.outer_iterations, in.layers);
    pyramid::StageTimes times;
    const pyramid::Pyramid built = bottomUp(in, iteration, times, out);
    addStageTimes(times, out);
    std::vector<Pose> updated;
    if (iteration == in.settings.outer_iterations && beside_last_graph) {
      // The pose graph keeps one thread (repeatable poses): the other
      // cores do what comes next and needs none of its poses.
      tbb::task_group beside;
      beside.run([&, points = out.layer_one_points] { beside_last_graph(points); });
      try {
        updated = topDown(in, start, built, iteration, out);
      } catch (...) {
        beside.cancel();
        try {
          beside.wait();
        } catch (...) {  // the pose graph's error is the one to report
        }
        throw;
      }
      beside.wait();
    } else {
      updated = topDown(in, start, built, iteration, out);
    }
    // The first process's pose graph speaks for all: members with other
    // thread counts (other machines) then still stop at the same iteration.
    if (in.group.size() > 1) updated = posesFromRoot(in.group, updated);
    const PoseChange u = largestChange(out.poses, updated);
    out.iterations.back().max_translation_update = u.translation_m;
    out.iterations.back().max_rotation_update = u.rotation_deg;
    spdlog::info("  largest pose update: {:.4f} m, {:.4f} deg", u.translation_m, u.rotation_deg);
    out.poses = std::move(updated);
    if (rounds.stopAfter(iteration, u)) break;
  }
  out.rounds_stopped = toString(rounds.why());
  out.rounds_reason = rounds.reason();
  spdlog::info("{}", out.rounds_reason);
  return out;
}

}  // namespace hba::pipeline
