#include "layer.hpp"

#include <algorithm>

namespace hba::pyramid {

Layer scanLayer(const std::vector<Pose>& poses) {
  Layer layer;
  layer.poses = poses;
  layer.nodes.resize(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) layer.nodes[i] = i;
  layer.distance_m.assign(poses.size(), 0.0);
  layer.as_input.assign(poses.size(), true);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    layer.distance_m[i] = layer.distance_m[i - 1] + (poses[i].t - poses[i - 1].t).norm();
  }
  return layer;
}

bool framesAsInput(const Layer& layer, const Window& window) {
  const auto first = layer.as_input.begin() + static_cast<long>(window.first);
  return std::all_of(first, first + static_cast<long>(window.count), [](bool as_input) { return as_input; });
}

}  // namespace hba::pyramid
