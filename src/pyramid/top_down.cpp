#include "top_down.hpp"

namespace hba::pyramid {

std::vector<Pose> directAssign(const std::vector<LayerOutcome>& outcomes, std::vector<Pose> top_poses) {
  std::vector<Pose> upper = std::move(top_poses);
  for (auto layer = outcomes.rbegin(); layer != outcomes.rend(); ++layer) {
    const std::vector<Window> plan = windowsOf(*layer);

    std::vector<Pose> lower(planFrames(plan));
    for (std::size_t j = 0; j < plan.size(); ++j) {
      const std::vector<Pose>& optimized = layer->windows[j].optimized;
      const Window own = ownFrames(plan, j);
      for (std::size_t k = 0; k < own.count; ++k) {
        lower[own.first + k] = upper.at(j) * relative(optimized.front(), optimized[k]);
      }
    }
    upper = std::move(lower);
  }
  return upper;
}

}  // namespace hba::pyramid
