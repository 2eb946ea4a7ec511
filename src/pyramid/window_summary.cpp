#include "window_summary.hpp"

#include <vector>

#include <spdlog/spdlog.h>

#include "hba/graph/window_factors.hpp"

namespace hba::pyramid {

WindowSummary summarizeWindow(const Layer& layer, const Window& window, const ba::BaResult& result,
                              const HbaSettings& settings) {
  WindowSummary out;
  out.outcome.window = window;
  out.outcome.optimized = result.poses;
  out.outcome.has_planes = result.num_planes > 0;
  out.outcome.kept_start = !result.trusted || result.settled;
  const auto first = layer.nodes.begin() + static_cast<long>(window.first);
  const std::vector<std::size_t> nodes(first, first + static_cast<long>(window.count));
  // Windows too large for one dense factor fall back to the paper's pairs.
  const bool joint =
      settings.factor_pairs == graph::FactorPairs::Joint && nodes.size() <= graph::kMaxJointFrames;
  if (joint) {
    out.outcome.shapes.push_back(
        graph::windowShapeFactor(result.hessian, result.poses, nodes, settings.information));
  } else {
    const graph::FactorPairs pairs = settings.factor_pairs == graph::FactorPairs::Joint
                                         ? graph::FactorPairs::Adjacent
                                         : settings.factor_pairs;
    out.outcome.factors =
        graph::windowFactors(result.hessian, result.poses, nodes, pairs, settings.information);
  }
  out.cost_before = result.initial_cost;
  out.cost_after = result.final_cost;
  out.planes = result.num_planes;
  out.plane_points = result.num_plane_points;
  out.iterations = result.iterations;
  out.rounds = result.rounds;
  out.trusted = result.trusted;
  out.settled = result.settled;
  out.solved_again = result.solved_again_at_input;
  spdlog::debug("  window of frames {}-{}: gained {:.2f} times what fitting noise would{}", window.first,
                window.first + window.count - 1, result.gain_over_noise,
                result.settled ? ", settled" : (result.trusted ? "" : ", not trusted"));
  for (double r : result.plane_rms_initial) out.sq_rms_before += r * r;
  for (double r : result.plane_rms_final) out.sq_rms_after += r * r;
  return out;
}

}  // namespace hba::pyramid
