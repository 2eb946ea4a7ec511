#pragma once
#include <vector>

#include "hba/ba/window_ba.hpp"
#include "hba/core/point_cloud.hpp"
#include "layer.hpp"

namespace hba::pyramid {

// The plane BA of one window of `layer`: it starts from the current poses
// of the window's frames (the first one is held: the gauge), and its motion
// prior measures the path between neighbouring frames along the layer.
// `clouds` are the window's frames' clouds, in order. Only a window of
// frames as the input made them may settle (Layer::as_input).
ba::BaResult runWindowBa(const Layer& layer, const Window& window,
                         const std::vector<const PointCloud*>& clouds, const ba::BaSettings& settings);

// Path (m) between each pair of neighbouring frames of a window.
std::vector<double> pathBetweenFrames(const Layer& layer, const Window& window);

}  // namespace hba::pyramid
