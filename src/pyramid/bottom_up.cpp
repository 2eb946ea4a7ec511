#include "bottom_up.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/progress.hpp"
#include "core/stopwatch.hpp"
#include "keyframe.hpp"
#include "layer_report_sum.hpp"
#include "streamed_clouds.hpp"
#include "window_batches.hpp"
#include "window_exchange.hpp"
#include "window_run.hpp"
#include "window_summary.hpp"

namespace hba::pyramid {

namespace {

// Each window's share of a layer's work: its points where they are known
// without reading (an upper layer's keyframes), else its scans' sizes as
// their source tells them (file bytes; 1 each where it cannot).
std::vector<double> windowWork(const Layer& layer, const std::vector<Window>& windows,
                               const io::ScanSource& clouds) {
  if (!layer.keyframe_points.empty()) {
    return workOf(windows, [&](std::size_t i) { return static_cast<double>(layer.keyframe_points.at(i)); });
  }
  return workOf(windows, [&](std::size_t i) { return clouds.sizeHint(i); });
}

}  // namespace

LayerOutcome optimizeLayer(const Layer& layer, const TimedClouds& clouds, const std::vector<Window>& windows,
                           const ba::BaSettings& ba_settings, const HbaSettings& settings,
                           const io::CloudStore* next, double keyframe_voxel, StageTimes& times,
                           const std::string& progress_label, const dist::Group& group,
                           const std::vector<Window>& next_windows) {
  checkWindowPlan(windows, layer.poses.size());
  std::vector<WindowSummary> summaries(windows.size());
  StreamedClouds streamed(clouds.source());
  const auto threads = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  const bool scans = layer.keyframes == nullptr;
  // This process's windows: all of them, or its range of a group's.
  const WindowRange mine = group.size() > 1 ? windowsOfMember(windowWork(layer, windows, clouds.source()),
                                                              group.rank(), group.size())
                                            : WindowRange{0, windows.size()};
  const std::vector<Window> my_windows(windows.begin() + static_cast<long>(mine.first),
                                       windows.begin() + static_cast<long>(mine.end));

  const LoadSeconds loaded_before = clouds.seconds();
  Progress progress(progress_label, my_windows.size(), "windows");
  for (WindowBatch batch : batchWindows(my_windows, windowsPerBatch(scans, threads))) {
    batch.first_window += mine.first;
    batch.end_window += mine.first;
    auto start = Clock::now();
    streamed.keepRange(batch.first_frame, batch.end_frame);
    times.load += secondsSince(start);

    start = Clock::now();
    const std::size_t b0 = batch.first_window;
    std::vector<ba::BaResult> ba_results(batch.end_window - b0);
    tbb::parallel_for(b0, batch.end_window, [&](std::size_t w) {
      ba_results[w - b0] = runWindowBa(layer, windows[w], streamed.cloudsOf(windows[w]), ba_settings);
      summaries[w] = summarizeWindow(layer, windows[w], ba_results[w - b0], settings);
      progress.advance();
    });
    times.ba += secondsSince(start);
    for (const ba::BaResult& result : ba_results) {
      times.associate += result.seconds_associate;
      times.solve += result.seconds_solve;
    }

    if (next) {
      start = Clock::now();
      tbb::parallel_for(b0, batch.end_window, [&](std::size_t w) {
        const ba::BaResult& result = ba_results[w - b0];
        next->store(w, buildKeyframe(streamed.cloudsOf(windows[w]), result.poses, result.plane_point_indices,
                                     keyframe_voxel));
      });
      times.keyframes += secondsSince(start);
    }
  }
  const LoadSeconds loaded_after = clouds.seconds();
  times.load_parts.read += loaded_after.read - loaded_before.read;
  times.load_parts.downsample += loaded_after.downsample - loaded_before.downsample;

  Shared shared;
  if (group.size() > 1) {
    shared = shareWindows(group, mine, summaries, next, next_windows, streamed);
  } else {
    shared.cloud_points = streamed.pointsLoaded();
    for (std::size_t w = 0; next && w < windows.size(); ++w)
      shared.keyframe_points.push_back(next->points(w));
  }

  LayerOutcome outcome;
  outcome.report = sumLayerReport(summaries);
  outcome.report.frames = layer.poses.size();
  outcome.report.cloud_points = shared.cloud_points;
  outcome.report.exchange_bytes = shared.bytes;
  outcome.report.exchange_bytes_largest = shared.largest;
  outcome.keyframe_points = std::move(shared.keyframe_points);
  outcome.windows.reserve(summaries.size());
  for (WindowSummary& summary : summaries) outcome.windows.push_back(std::move(summary.outcome));
  return outcome;
}

}  // namespace hba::pyramid
