#include "upper_layer.hpp"

#include <vector>

namespace hba::pyramid {

Layer buildUpperLayer(const Layer& lower, const LayerOutcome& outcome,
                      std::unique_ptr<io::CloudStore> keyframes) {
  const std::vector<Window> plan = windowsOf(outcome);

  Layer upper;
  const std::size_t n = plan.size();
  upper.nodes.reserve(n);
  upper.poses.reserve(n);
  upper.distance_m.reserve(n);
  for (std::size_t j = 0; j < n; ++j) {
    upper.nodes.push_back(lower.nodes[plan[j].first]);
    upper.distance_m.push_back(lower.distance_m[plan[j].first]);
    upper.as_input.push_back(outcome.windows[j].kept_start && framesAsInput(lower, plan[j]));
    if (j == 0) {
      upper.poses.push_back(outcome.windows[j].optimized.front());
    } else {
      // Window j starts where window j-1's own frames end.
      const std::vector<Pose>& previous = outcome.windows[j - 1].optimized;
      const std::size_t start_in_previous = ownFrames(plan, j - 1).count;
      upper.poses.push_back(upper.poses.back() * relative(previous.front(), previous.at(start_in_previous)));
    }
  }
  upper.keyframes = std::move(keyframes);
  upper.keyframe_points = outcome.keyframe_points;
  return upper;
}

}  // namespace hba::pyramid
