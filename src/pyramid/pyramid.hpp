#pragma once
// The paper's method (Liu et al. 2023, Sec. III): bottom-up plane BA over a
// pyramid of keyframes, then the top-down pose graph back to every scan.
// One pass of each; the pipeline repeats them until the poses settle, and
// times, logs and reports them (src/pipeline/pyramid_stage.cpp).
#include <functional>
#include <vector>

#include "bottom_up.hpp"
#include "hba/graph/factors.hpp"

namespace hba::pyramid {

// What the bottom-up pass left: every window's outcome, layer by layer.
struct Pyramid {
  std::vector<LayerOutcome> local;  // layers 1 .. l-1
  LayerOutcome top;                 // layer l: one window, the global BA
};

// What the method does not need but its caller does: the process group the
// windows are spread over, where the time goes, and a look at each layer
// as it ends (its frames as the windows began, its outcome).
struct LayerWatch {
  explicit LayerWatch(const dist::Group& group_in = dist::singleProcess()) : group(group_in) {}
  const dist::Group& group;
  StageTimes times;
  std::function<void(int level, const Layer& layer, LayerOutcome& outcome)> layer_done = nullptr;
};

// Bottom-up (Sec. III-B) from `poses`: `layers` layers, the last one global.
Pyramid bottomUp(const TimedClouds& scans, const std::vector<Pose>& poses, int layers,
                 const HbaSettings& settings, LayerWatch& watch);

// The top-down pass's poses and its pose graph's figures.
struct TopDown {
  std::vector<Pose> poses;
  std::size_t factors = 0;  // 0: the direct assignment, no pose graph
  double cost_before = 0.0;
  double cost_after = 0.0;
};

// Top-down (Sec. III-C): every window's factors, with `loops` and `priors`,
// in one pose graph over the layer-1 poses, solved from the direct
// assignment (or that assignment alone, settings.top_down).
TopDown topDown(const Pyramid& pyramid, const std::vector<graph::LoopClosureFactor>& loops,
                const std::vector<graph::PositionPriorFactor>& priors, const HbaSettings& settings);

// The BA settings of layer `level`'s windows (the top's is the global BA).
ba::BaSettings windowSettings(const HbaSettings& settings, int level, bool top);

}  // namespace hba::pyramid
