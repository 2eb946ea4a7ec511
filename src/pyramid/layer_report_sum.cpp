#include "layer_report_sum.hpp"

#include <cmath>

namespace hba::pyramid {

LayerReport sumLayerReport(const std::vector<WindowSummary>& windows) {
  LayerReport report;
  report.windows = windows.size();
  double sq_before = 0.0;
  double sq_after = 0.0;
  for (const WindowSummary& w : windows) {
    report.planes += w.planes;
    report.plane_points += w.plane_points;
    report.lm_iterations += static_cast<std::size_t>(w.iterations);
    report.association_rounds += static_cast<std::size_t>(w.rounds);
    report.cost_before += w.cost_before;
    report.cost_after += w.cost_after;
    sq_before += w.sq_rms_before;
    sq_after += w.sq_rms_after;
    if (!w.outcome.has_planes) ++report.windows_without_planes;
    if (!w.trusted) ++report.windows_untrusted;
    if (w.settled) ++report.windows_settled;
    if (w.solved_again) ++report.windows_solved_again;
  }
  if (report.planes > 0) {
    report.rms_before = std::sqrt(sq_before / static_cast<double>(report.planes));
    report.rms_after = std::sqrt(sq_after / static_cast<double>(report.planes));
  }
  return report;
}

}  // namespace hba::pyramid
