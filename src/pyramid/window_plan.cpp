#include "hba/pyramid/window_plan.hpp"

#include "hba/core/error.hpp"

namespace hba::pyramid {

std::vector<Window> planWindows(std::size_t frames, int window, int stride) {
  if (window < 2) throw Error("window size must be at least 2 (got " + std::to_string(window) + ")");
  if (stride < 1 || stride >= window) {
    throw Error("stride must be in [1, window - 1] so that windows overlap (got stride " +
                std::to_string(stride) + ", window " + std::to_string(window) + ")");
  }
  std::vector<Window> windows;
  if (frames == 0) return windows;
  const auto w = static_cast<std::size_t>(window);
  const auto s = static_cast<std::size_t>(stride);
  if (frames <= w) return {Window{0, frames}};
  for (std::size_t first = 0;; first += s) {
    const std::size_t end = std::min(first + w, frames);
    windows.push_back(Window{first, end - first});
    if (end == frames) break;
  }
  return windows;
}

}  // namespace hba::pyramid
