#include "hba/pyramid/window_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hba/core/error.hpp"

namespace hba::pyramid {
namespace {

std::string describe(const std::vector<Window>& windows, std::size_t j) {
  const Window& w = windows[j];
  return "window " + std::to_string(j) + " (frames " + std::to_string(w.first) + "-" +
         std::to_string(w.first + w.count - 1) + ")";
}

}  // namespace

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

void checkWindowPlan(const std::vector<Window>& windows, std::size_t frames) {
  const std::string layer = "window plan of a layer of " + std::to_string(frames) + " frames: ";
  if (windows.empty()) throw Error(layer + "no windows");
  for (std::size_t j = 0; j < windows.size(); ++j) {
    if (windows[j].count == 0) throw Error(layer + "window " + std::to_string(j) + " is empty");
  }
  if (windows.front().first != 0) throw Error(layer + describe(windows, 0) + " does not start at frame 0");
  for (std::size_t j = 1; j < windows.size(); ++j) {
    const Window& previous = windows[j - 1];
    if (windows[j].first <= previous.first || windows[j].first >= previous.first + previous.count) {
      throw Error(layer + describe(windows, j) + " does not start inside " + describe(windows, j - 1) +
                  " after its first frame");
    }
  }
  if (planFrames(windows) != frames) {
    throw Error(layer + "the windows end at frame " + std::to_string(planFrames(windows)));
  }
}

Window ownFrames(const std::vector<Window>& windows, std::size_t j) {
  const Window& window = windows.at(j);
  if (j + 1 == windows.size()) return window;
  return Window{window.first, windows[j + 1].first - window.first};
}

std::size_t planFrames(const std::vector<Window>& windows) {
  std::size_t end = 0;
  for (const Window& w : windows) end = std::max(end, w.first + w.count);
  return end;
}

int maxLayerCount(std::size_t frames, int window, int stride) {
  int layers = 1;
  // Another layer pays off only while the current one has more than one window.
  for (auto plan = planWindows(frames, window, stride); plan.size() > 1;
       plan = planWindows(plan.size(), window, stride)) {
    ++layers;
  }
  return layers;
}

int paperLayerCount(std::size_t frames, int window, int stride, int threads) {
  const double n = std::max(threads, 1);
  const double N = static_cast<double>(frames);
  const double s = stride;
  const double w = window;
  const double arg = 3.0 * N * N * (s * s * s - s) * n / (w * w * w);
  int layers = arg > 1.0 ? static_cast<int>(std::floor(0.5 * std::log(arg) / std::log(s))) : 1;
  return std::clamp(layers, 1, maxLayerCount(frames, window, stride));
}

int defaultLayerCount(std::size_t frames, const HbaSettings& settings) {
  constexpr int kPaperThreads = 8;  // Table I of the paper
  return paperLayerCount(frames, settings.window, settings.stride, kPaperThreads);
}

int layerCount(std::size_t frames, const HbaSettings& settings) {
  if (settings.window <= 0 || settings.stride <= 0)
    throw Error("layerCount: the window is automatic; choose it first (window_size.hpp)");
  return settings.layers > 0
             ? std::min(settings.layers, maxLayerCount(frames, settings.window, settings.stride))
             : defaultLayerCount(frames, settings);
}

}  // namespace hba::pyramid
