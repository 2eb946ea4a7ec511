#include "window_run.hpp"

namespace hba::pyramid {

std::vector<double> pathBetweenFrames(const Layer& layer, const Window& window) {
  std::vector<double> path;
  for (std::size_t k = window.first; k + 1 < window.first + window.count; ++k) {
    path.push_back(layer.distance_m[k + 1] - layer.distance_m[k]);
  }
  return path;
}

ba::BaResult runWindowBa(const Layer& layer, const Window& window,
                         const std::vector<const PointCloud*>& clouds, const ba::BaSettings& settings) {
  const auto first_pose = layer.poses.begin() + static_cast<long>(window.first);
  const std::vector<Pose> initial(first_pose, first_pose + static_cast<long>(window.count));
  ba::BaSettings window_settings = settings;
  if (!framesAsInput(layer, window))
    window_settings.significant_gain = 0.0;  // above moved frames: no settling
  return ba::optimizeWindow(clouds, initial, window_settings, pathBetweenFrames(layer, window));
}

}  // namespace hba::pyramid
