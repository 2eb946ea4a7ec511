#pragma once
#include "hba/pyramid/scan_source.hpp"
#include "hba/pyramid/settings.hpp"
#include "layer.hpp"

namespace hba::pyramid {

struct StageTimes {
  double load = 0.0;
  double ba = 0.0;
  double keyframes = 0.0;
};

// Runs one BA per window of `layer` (in parallel) and turns each window's
// Hessian into pose-graph factors. With `source` set, the layer is layer 1
// and its clouds are streamed from it in batches, so memory stays bounded by
// a few windows' worth of scans. With `build_keyframes`, each window's plane
// points become the keyframe of the next layer.
LayerOutcome optimizeLayer(const Layer& layer, const ScanSource* source,
                           const std::vector<Window>& windows, const ba::BaSettings& ba_settings,
                           const HbaSettings& settings, bool build_keyframes, StageTimes& times);

// Layer i+1 from layer i's windows: keyframe j is window j, anchored at its
// first frame, posed by chaining the windows' optimized relative poses
// (the paper's eq. 1), so local corrections reach the upper layer.
Layer buildUpperLayer(const Layer& lower, LayerOutcome& outcome, int stride);

}  // namespace hba::pyramid
