#pragma once
#include <vector>

#include "hba/pyramid/layer_report.hpp"
#include "window_summary.hpp"

namespace hba::pyramid {

// A layer's report from its windows' summaries: the window count, counts
// and costs summed over windows, the windows without planes or not trusted,
// and the RMS over all planes of the layer (each plane weighs the same,
// whichever window found it). Frames, cloud points, times and the layer's
// place in the pyramid are the caller's to fill in.
LayerReport sumLayerReport(const std::vector<WindowSummary>& windows);

}  // namespace hba::pyramid
