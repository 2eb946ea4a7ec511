#pragma once
// Which frames of a layer each local window covers. Everything after the
// plan (keyframe poses and nodes, direct assignment, the next layer's
// size) reads the windows' own first frame and count, never a stride, so a
// plan with uneven windows works unchanged.
#include <cstddef>
#include <vector>

#include "hba/settings/settings.hpp"

namespace hba::pyramid {

struct Window {
  std::size_t first = 0;  // index of the window's first frame in its layer
  std::size_t count = 0;  // frames in the window
};

// Windows of `window` frames starting every `stride` frames, so that every
// frame is in a window: the last window starts at the last multiple of the
// stride that leaves a frame uncovered and may be shorter than `window` (it
// still overlaps its predecessor by window - stride frames). A layer with
// at most `window` frames is one window. Keyframe j of the next layer is
// window j, anchored at the window's first frame.
std::vector<Window> planWindows(std::size_t frames, int window, int stride);

// Throws hba::Error unless `windows` is a usable plan of a layer of
// `frames` frames: the first window starts at frame 0, each later window
// starts after its predecessor and inside it (so keyframe poses chain),
// and the last one ends at the layer's last frame.
void checkWindowPlan(const std::vector<Window>& windows, std::size_t frames);

// The frames keyframe j stands for when its pose is handed down: from its
// window's first frame up to the next window's first frame; the last window
// stands for all its frames. `windows` must be a plan (checkWindowPlan).
Window ownFrames(const std::vector<Window>& windows, std::size_t j);

// Frames of the layer a plan covers (the end of its last window).
std::size_t planFrames(const std::vector<Window>& windows);

// Largest layer count for which every layer below the top has more than one
// window (the top layer then holds at least `window` frames, or the whole
// sequence if it is shorter). Layer i+1 has one frame per window of layer i.
int maxLayerCount(std::size_t frames, int window, int stride);

// The paper's optimal layer count l* = floor(1/2 log_s(3 N^2 (s^3 - s) n / w^3)),
// clamped to [1, the number of layers the sequence can hold].
int paperLayerCount(std::size_t frames, int window, int stride, int threads);
// The layer count hba uses when settings.layers == 0: the paper's formula
// with its own n = 8 threads, whatever this machine has, so that the same
// command builds the same pyramid (and gives the same poses) everywhere.
int defaultLayerCount(std::size_t frames, const HbaSettings& settings);
// The layers a run of `settings` over `frames` builds: settings.layers, at
// most what the sequence holds, or (0) the default rule.
int layerCount(std::size_t frames, const HbaSettings& settings);

}  // namespace hba::pyramid
