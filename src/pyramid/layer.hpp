#pragma once
// Internal data of the pyramid: a layer's frames and what its windows produced.
#include <cstddef>
#include <memory>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/pyramid/layer_report.hpp"
#include "hba/pyramid/window_plan.hpp"
#include "hba/settings/settings.hpp"
#include "io/cloud_store.hpp"

namespace hba::pyramid {

// The frames of one layer. Every layer streams its clouds: layer 1 from the
// input scans, upper layers from their keyframe store on disk.
struct Layer {
  std::vector<std::size_t> nodes;  // pose-graph node of each frame: the layer-1 scan it starts at
  std::vector<Pose> poses;         // current world poses of the frames
  // Path length (m) along the layer-1 poses from the first frame to each
  // frame: how far apart two frames are, for the motion prior.
  std::vector<double> distance_m;
  // Each frame as the input made it: layer 1's scans, and above, keyframes
  // of windows that kept their start poses and held only such frames. Only
  // a window of such frames may settle (BaSettings::significant_gain):
  // above frames that moved, a window's gain includes re-aligning what
  // the windows below moved, which is no test of the input.
  std::vector<bool> as_input;
  std::unique_ptr<io::CloudStore> keyframes;  // null for layer 1
  // The points of every keyframe, also of those stored by other processes
  // only (a group spreads the windows by them); empty for layer 1.
  std::vector<std::size_t> keyframe_points;
};

// Layer 1: the input frames at `poses`, each anchored at itself, with the
// path along the poses.
Layer scanLayer(const std::vector<Pose>& poses);

// What the BA of one window left behind (its Hessian is turned into
// factors at once, so it is not kept).
struct WindowOutcome {
  Window window;
  std::vector<Pose> optimized;  // frame 0 keeps its input pose (gauge)
  std::vector<graph::RelativePoseFactor> factors;
  std::vector<graph::WindowShapeFactor> shapes;  // one under FactorPairs::Joint, else none
  bool has_planes = false;
  bool kept_start = false;  // optimized == its start poses (not trusted, or settled)
};

struct LayerOutcome {
  std::vector<WindowOutcome> windows;
  LayerReport report;
  std::vector<std::size_t> keyframe_points;  // of each window's keyframe, when it made them
};

// Every frame of `window` is as the input made it (Layer::as_input).
bool framesAsInput(const Layer& layer, const Window& window);

// The plan a layer's windows followed.
inline std::vector<Window> windowsOf(const LayerOutcome& outcome) {
  std::vector<Window> plan;
  plan.reserve(outcome.windows.size());
  for (const WindowOutcome& window : outcome.windows) plan.push_back(window.window);
  return plan;
}

}  // namespace hba::pyramid
