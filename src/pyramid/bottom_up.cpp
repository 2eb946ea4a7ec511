#include "bottom_up.hpp"

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "hba/core/progress.hpp"
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "hba/graph/window_factors.hpp"
#include "keyframe.hpp"
#include "hba/core/stopwatch.hpp"

namespace hba::pyramid {
namespace {

struct WindowBa {
  WindowOutcome outcome;
  double cost_before = 0.0;
  double cost_after = 0.0;
  double sq_rms_before = 0.0;  // sum over planes of rms^2
  double sq_rms_after = 0.0;
  std::size_t planes = 0;
  std::size_t plane_points = 0;
  int iterations = 0;
  int rounds = 0;
  bool trusted = true;
};

WindowBa summarize(const Layer& layer, const ba::BaResult& result, const Window& window,
                   const HbaSettings& settings) {
  WindowBa out;
  out.outcome.window = window;
  out.outcome.optimized = result.poses;
  out.outcome.has_planes = result.num_planes > 0;
  const auto first = layer.anchors.begin() + static_cast<long>(window.first);
  const std::vector<std::size_t> anchors(first, first + static_cast<long>(window.count));
  out.outcome.factors = graph::windowFactors(result.hessian, result.poses, anchors,
                                             settings.factor_pairs, settings.information);
  out.cost_before = result.initial_cost;
  out.cost_after = result.final_cost;
  out.planes = result.num_planes;
  out.plane_points = result.num_plane_points;
  out.iterations = result.iterations;
  out.rounds = result.rounds;
  out.trusted = result.trusted;
  for (double r : result.plane_rms_initial) out.sq_rms_before += r * r;
  for (double r : result.plane_rms_final) out.sq_rms_after += r * r;
  return out;
}

// The clouds (scans or keyframes) of a range of frames, loaded in parallel and dropped once
// no later window needs them.
class StreamedClouds {
 public:
  explicit StreamedClouds(const ScanSource& source) : source_(source) {}

  void keepRange(std::size_t first, std::size_t end) {
    for (auto it = cache_.begin(); it != cache_.end();) {
      it = it->first < first ? cache_.erase(it) : std::next(it);
    }
    std::vector<std::size_t> missing;
    for (std::size_t i = first; i < end; ++i) {
      if (!cache_.count(i)) missing.push_back(i);
    }
    std::vector<PointCloud> loaded(missing.size());
    tbb::parallel_for(std::size_t{0}, missing.size(),
                      [&](std::size_t k) { loaded[k] = source_.load(missing[k]); });
    for (std::size_t k = 0; k < missing.size(); ++k) cache_[missing[k]] = std::move(loaded[k]);
  }

  const PointCloud* get(std::size_t i) const { return &cache_.at(i); }

 private:
  const ScanSource& source_;
  std::map<std::size_t, PointCloud> cache_;
};

// Path (m) between neighbouring frames of a window.
std::vector<double> pathBetweenFrames(const Layer& layer, const Window& window) {
  std::vector<double> path;
  for (std::size_t k = window.first; k + 1 < window.first + window.count; ++k) {
    path.push_back(layer.distance_m[k + 1] - layer.distance_m[k]);
  }
  return path;
}

}  // namespace

LayerOutcome optimizeLayer(const Layer& layer, const ScanSource& clouds,
                           const std::vector<Window>& windows, const ba::BaSettings& ba_settings,
                           const HbaSettings& settings, const KeyframeStore* next,
                           double keyframe_voxel, StageTimes& times, const std::string& progress_label) {
  LayerOutcome outcome;
  outcome.windows.resize(windows.size());
  std::vector<WindowBa> results(windows.size());

  StreamedClouds streamed(clouds);
  const std::size_t concurrency = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  // Layer-1 scans are small: batches of several windows per thread keep the
  // threads busy. Keyframes grow with the layer: one window per thread.
  const bool scans = layer.keyframes == nullptr;
  const std::size_t batch = std::max<std::size_t>(scans ? 4 : 1, (scans ? 4 : 1) * concurrency);

  const LoadSeconds loaded_before = clouds.loadSeconds();
  std::size_t cloud_points = 0;
  std::size_t counted_end = 0;  // frames whose points are counted
  Progress progress(progress_label, windows.size(), "windows");
  for (std::size_t b0 = 0; b0 < windows.size(); b0 += batch) {
    const std::size_t b1 = std::min(windows.size(), b0 + batch);
    auto start = Clock::now();
    const std::size_t first = windows[b0].first;
    const std::size_t end = windows[b1 - 1].first + windows[b1 - 1].count;
    streamed.keepRange(first, end);
    for (std::size_t i = std::max(first, counted_end); i < end; ++i) {
      cloud_points += streamed.get(i)->size();
    }
    counted_end = end;
    times.load += secondsSince(start);
    auto cloudsOf = [&](const Window& window) {
      std::vector<const PointCloud*> window_clouds(window.count);
      for (std::size_t k = 0; k < window.count; ++k) window_clouds[k] = streamed.get(window.first + k);
      return window_clouds;
    };

    start = Clock::now();
    std::vector<ba::BaResult> ba_results(b1 - b0);
    tbb::parallel_for(b0, b1, [&](std::size_t w) {
      const Window& window = windows[w];
      const auto first_pose = layer.poses.begin() + static_cast<long>(window.first);
      const std::vector<Pose> initial(first_pose, first_pose + static_cast<long>(window.count));
      ba_results[w - b0] =
          ba::optimizeWindow(cloudsOf(window), initial, ba_settings, pathBetweenFrames(layer, window));
      results[w] = summarize(layer, ba_results[w - b0], window, settings);
      progress.advance();
    });
    times.ba += secondsSince(start);
    for (const ba::BaResult& result : ba_results) {
      times.associate += result.seconds_associate;
      times.solve += result.seconds_solve;
    }

    if (next) {
      start = Clock::now();
      tbb::parallel_for(b0, b1, [&](std::size_t w) {
        const ba::BaResult& result = ba_results[w - b0];
        next->store(w, buildKeyframe(cloudsOf(windows[w]), result.poses,
                                     result.plane_point_indices, keyframe_voxel));
      });
      times.keyframes += secondsSince(start);
    }
  }

  const LoadSeconds loaded_after = clouds.loadSeconds();
  times.load_parts.read += loaded_after.read - loaded_before.read;
  times.load_parts.downsample += loaded_after.downsample - loaded_before.downsample;

  LayerReport& report = outcome.report;
  report.frames = layer.poses.size();
  report.windows = windows.size();
  report.cloud_points = cloud_points;
  double sq_before = 0.0;
  double sq_after = 0.0;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    WindowBa& r = results[w];
    report.planes += r.planes;
    report.plane_points += r.plane_points;
    report.lm_iterations += static_cast<std::size_t>(r.iterations);
    report.association_rounds += static_cast<std::size_t>(r.rounds);
    report.cost_before += r.cost_before;
    report.cost_after += r.cost_after;
    sq_before += r.sq_rms_before;
    sq_after += r.sq_rms_after;
    if (!r.outcome.has_planes) ++report.windows_without_planes;
    if (!r.trusted) ++report.windows_untrusted;
    outcome.windows[w] = std::move(r.outcome);
  }
  if (report.planes > 0) {
    report.rms_before = std::sqrt(sq_before / static_cast<double>(report.planes));
    report.rms_after = std::sqrt(sq_after / static_cast<double>(report.planes));
  }
  return outcome;
}

}  // namespace hba::pyramid
