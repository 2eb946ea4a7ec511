#pragma once
// Internal data of the pyramid: a layer's frames and what its windows produced.
#include <cstddef>
#include <memory>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/graph/pose_graph.hpp"
#include "hba/pyramid/hierarchical_ba.hpp"
#include "hba/pyramid/window_plan.hpp"
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
};

struct LayerOutcome {
  std::vector<WindowOutcome> windows;
  LayerReport report;
  std::vector<std::size_t> keyframe_points;  // of each window's keyframe, when it made them
};

// The plan a layer's windows followed.
inline std::vector<Window> windowsOf(const LayerOutcome& outcome) {
  std::vector<Window> plan;
  plan.reserve(outcome.windows.size());
  for (const WindowOutcome& window : outcome.windows) plan.push_back(window.window);
  return plan;
}

}  // namespace hba::pyramid
