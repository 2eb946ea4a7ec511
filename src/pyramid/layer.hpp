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

namespace hba::pyramid {

// The frames of one layer. Layer 1 streams its clouds from a ScanSource;
// upper layers hold their keyframe clouds in memory.
struct Layer {
  std::vector<std::size_t> anchors;  // layer-1 index of each frame
  std::vector<Pose> poses;           // current world poses of the frames
  std::vector<PointCloud> clouds;    // keyframe clouds (empty for layer 1)
};

// What the BA of one window left behind (its Hessian is turned into
// factors at once, so it is not kept).
struct WindowOutcome {
  Window window;
  std::vector<Pose> optimized;  // frame 0 keeps its input pose (gauge)
  std::vector<graph::RelativePoseFactor> factors;
  PointCloud keyframe;  // plane points in the frame of the window's first frame
  bool has_planes = false;
};

struct LayerOutcome {
  std::vector<WindowOutcome> windows;
  LayerReport report;
};

}  // namespace hba::pyramid
