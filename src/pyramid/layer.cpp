#include "layer.hpp"

namespace hba::pyramid {

Layer scanLayer(const std::vector<Pose>& poses) {
  Layer layer;
  layer.poses = poses;
  layer.nodes.resize(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) layer.nodes[i] = i;
  layer.distance_m.assign(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    layer.distance_m[i] = layer.distance_m[i - 1] + (poses[i].t - poses[i - 1].t).norm();
  }
  return layer;
}

}  // namespace hba::pyramid
