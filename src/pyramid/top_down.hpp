#pragma once
#include <vector>

#include "hba/core/pose.hpp"
#include "layer.hpp"

namespace hba::pyramid {

// The paper's "direct assign": each upper pose moves the frames its keyframe
// stands for (ownFrames: from its window's first frame up to the next
// window's first; the last window: all its frames) rigidly with it, keeping
// the window's optimized relative poses, from the top layer down to layer 1.
// `outcomes[i]` holds the windows of layer i+1 (1-based), which must form a
// plan (checkWindowPlan); `top_poses` are the optimized poses of the top layer.
std::vector<Pose> directAssign(const std::vector<LayerOutcome>& outcomes, std::vector<Pose> top_poses);

}  // namespace hba::pyramid
