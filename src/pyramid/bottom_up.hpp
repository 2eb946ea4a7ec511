#pragma once
#include <string>
#include <vector>

#include "hba/dist/group.hpp"
#include "hba/settings/settings.hpp"
#include "io/cloud_store.hpp"
#include "layer.hpp"
#include "timed_clouds.hpp"

namespace hba::pyramid {

// Wall time of the phases, and thread time of their parts: the report
// splits each phase's wall time between its parts in proportion.
struct StageTimes {
  double load = 0.0;  // wall: reading (+ downsampling) clouds
  double ba = 0.0;    // wall: window BAs
  double keyframes = 0.0;
  LoadSeconds load_parts;  // thread time
  double associate = 0.0;  // thread time of the BAs: finding planes ...
  double solve = 0.0;      // ... and LM
};

// Runs one BA per window of `layer` (in parallel) and turns each window's
// Hessian into pose-graph factors. `windows` must form a plan of the layer
// (checkWindowPlan). The layer's clouds are streamed from `clouds` in
// batches (window_batches.hpp; their load times added to `times`), so memory stays bounded by a few windows'
// worth of clouds. With `next` set, each window's plane points, downsampled
// to `keyframe_voxel`, are stored there as keyframe j of the next layer.
// In a group of processes each runs its range of the windows (reading only
// their clouds), then has every window's summary and the keyframes its
// windows of the next layer (`next_windows`, the next layer's plan) read
// (window_exchange.hpp); every member must call it, for the same layer.
LayerOutcome optimizeLayer(const Layer& layer, const TimedClouds& clouds, const std::vector<Window>& windows,
                           const ba::BaSettings& ba_settings, const HbaSettings& settings,
                           const io::CloudStore* next, double keyframe_voxel, StageTimes& times,
                           const std::string& progress_label,
                           const dist::Group& group = dist::singleProcess(),
                           const std::vector<Window>& next_windows = {});

}  // namespace hba::pyramid
