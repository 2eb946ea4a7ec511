#pragma once
#include <memory>

#include "io/cloud_store.hpp"
#include "layer.hpp"

namespace hba::pyramid {

// Layer i+1 from layer i's windows: keyframe j is window j, anchored at the
// window's first frame, posed by chaining the windows' optimized relative
// poses (the paper's eq. 1): T_j = T_{j-1} * (pose of window j's first frame
// relative to window j-1's, in window j-1's result), so local corrections
// reach the upper layer. The windows must form a plan (checkWindowPlan).
Layer buildUpperLayer(const Layer& lower, const LayerOutcome& outcome,
                      std::unique_ptr<io::CloudStore> keyframes);

}  // namespace hba::pyramid
