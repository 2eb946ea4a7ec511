#include "pyramid.hpp"

#include <algorithm>
#include <memory>
#include <string>
#include <utility>

#include "hba/graph/pose_graph.hpp"
#include "top_down.hpp"
#include "upper_layer.hpp"

namespace hba::pyramid {
namespace {

// The windows of a layer of `frames`: w frames every s, or (the top) all.
std::vector<Window> planLayer(std::size_t frames, const HbaSettings& settings, bool top) {
  return top ? std::vector<Window>{Window{0, frames}} : planWindows(frames, settings.window, settings.stride);
}

// The clouds `layer` reads: layer 1 the scans, an upper layer its stored
// keyframes (held in `stored`).
const TimedClouds& cloudsOf(const Layer& layer, const TimedClouds& scans,
                            std::unique_ptr<TimedClouds>& stored) {
  if (!layer.keyframes) return scans;
  stored = std::make_unique<TimedClouds>(*layer.keyframes);
  return *stored;
}

std::string progressLabel(int level, bool top) {
  return "layer " + std::to_string(level) + (top ? " (global BA)" : "");
}

}  // namespace

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
  // Layer 1 may start finer, but never below the final voxel (coarsened
  // for sparse scans: final_voxel.hpp).
  ba::BaSettings window = settings.localBa();
  if (level == 1 && settings.scan_window_voxel > 0.0)
    window.planes.voxel_size = std::max(settings.scan_window_voxel, window.final_voxel_size);
  return window;
}

// Each layer's windows are optimized by plane BA, in parallel; their plane
// points, merged at the optimized relative poses, become the keyframes of
// the next layer (eq. FT), up to the top layer's one global BA.
Pyramid bottomUp(const TimedClouds& scans, const std::vector<Pose>& poses, int layers,
                 const HbaSettings& settings, LayerWatch& watch) {
  Pyramid pyramid;
  Layer layer = scanLayer(poses);
  for (int level = 1; level <= layers; ++level) {
    const bool top = level == layers;
    const std::vector<Window> windows = planLayer(layer.poses.size(), settings, top);
    std::unique_ptr<TimedClouds> stored;
    auto keyframes = top ? nullptr : std::make_unique<io::CloudStore>(windows.size());
    const std::vector<Window> next =
        top ? std::vector<Window>{} : planLayer(windows.size(), settings, level + 1 == layers);
    LayerOutcome outcome =
        optimizeLayer(layer, cloudsOf(layer, scans, stored), windows, windowSettings(settings, level, top),
                      settings, keyframes.get(), top ? 0.0 : keyframeVoxel(settings, level + 1), watch.times,
                      progressLabel(level, top), watch.group, next);
    if (watch.layer_done) watch.layer_done(level, layer, outcome);
    if (top) {
      pyramid.top = std::move(outcome);
    } else {
      layer = buildUpperLayer(layer, outcome, std::move(keyframes));
      pyramid.local.push_back(std::move(outcome));
    }
  }
  return pyramid;
}

// Every window's relative poses and Hessian become factors between layer-1
// poses (eq. layer_factor); the windows know nothing of the loops, and the
// priors set the frame.
TopDown topDown(const Pyramid& pyramid, const std::vector<graph::LoopClosureFactor>& loops,
                const std::vector<graph::PositionPriorFactor>& priors, const HbaSettings& settings) {
  TopDown out;
  out.poses = directAssign(pyramid.local, pyramid.top.windows.front().optimized);
  if (settings.top_down == TopDownMode::DirectAssign) return out;
  graph::FactorGraph graph;
  auto addWindow = [&graph](const WindowOutcome& window) {
    for (const auto& factor : window.factors) graph.add(factor);
    for (const auto& shape : window.shapes) graph.add(shape);
  };
  addWindow(pyramid.top.windows.front());
  for (const LayerOutcome& layer : pyramid.local) {
    for (const WindowOutcome& window : layer.windows) addWindow(window);
  }
  for (const auto& loop : loops) graph.add(loop);
  for (const auto& prior : priors) graph.add(prior);
  graph::PoseGraphSettings graph_settings = settings.graph;
  graph_settings.threads = settings.threads;
  const graph::PoseGraphResult solved = graph::optimizeFactorGraph(out.poses, graph, graph_settings);
  out.poses = solved.poses;
  out.factors = graph.size();
  out.cost_before = solved.initial_cost;
  out.cost_after = solved.final_cost;
  return out;
}

}  // namespace hba::pyramid
