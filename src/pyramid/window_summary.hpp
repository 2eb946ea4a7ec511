#pragma once
#include <cstddef>

#include "hba/ba/window_ba.hpp"
#include "hba/settings/settings.hpp"
#include "layer.hpp"

namespace hba::pyramid {

// What a window's BA leaves for the pyramid (its outcome: poses and
// pose-graph factors) and for the layer's report (its figures).
struct WindowSummary {
  WindowOutcome outcome;
  double cost_before = 0.0;
  double cost_after = 0.0;
  double sq_rms_before = 0.0;  // sum over planes of rms^2
  double sq_rms_after = 0.0;
  std::size_t planes = 0;
  std::size_t plane_points = 0;
  int iterations = 0;
  int rounds = 0;
  bool trusted = true;
  bool settled = false;
  bool solved_again = false;  // ba::BaResult::solved_again_at_input
};

// The summary of `window` of `layer` from its BA result. The BA's Hessian
// becomes factors between the layer-1 frames the window's frames anchor
// (settings.factor_pairs, settings.information), so it need not be kept.
WindowSummary summarizeWindow(const Layer& layer, const Window& window, const ba::BaResult& result,
                              const HbaSettings& settings);

}  // namespace hba::pyramid
