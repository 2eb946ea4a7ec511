#pragma once
#include <vector>

#include "hba/core/pose.hpp"
#include "layer.hpp"

namespace hba::pyramid {

// The paper's "direct assign": each upper pose moves the first `stride`
// frames of its window (the last window: all its frames) rigidly with it,
// keeping the window's optimized relative poses, from the top layer down to
// layer 1. `outcomes[i]` holds the windows of layer i+1 (1-based);
// `top_poses` are the optimized poses of the top layer.
std::vector<Pose> directAssign(const std::vector<LayerOutcome>& outcomes,
                               std::vector<Pose> top_poses, int stride);

}  // namespace hba::pyramid
