#include "top_down.hpp"

#include <algorithm>

namespace hba::pyramid {

std::vector<Pose> directAssign(const std::vector<LayerOutcome>& outcomes,
                               std::vector<Pose> top_poses, int stride) {
  std::vector<Pose> upper = std::move(top_poses);
  const auto s = static_cast<std::size_t>(stride);
  for (auto layer = outcomes.rbegin(); layer != outcomes.rend(); ++layer) {
    const auto& windows = layer->windows;
    const std::size_t frames = windows.empty() ? 0 : windows.back().window.first + windows.back().window.count;
    std::vector<Pose> lower(frames);
    for (std::size_t j = 0; j < windows.size(); ++j) {
      const WindowOutcome& w = windows[j];
      const bool last = j + 1 == windows.size();
      const std::size_t assigned = last ? w.window.count : std::min(s, w.window.count);
      for (std::size_t k = 0; k < assigned; ++k) {
        lower[w.window.first + k] = upper[j] * relative(w.optimized.front(), w.optimized[k]);
      }
    }
    upper = std::move(lower);
  }
  return upper;
}

}  // namespace hba::pyramid
