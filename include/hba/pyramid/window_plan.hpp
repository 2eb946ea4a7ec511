#pragma once
// Which frames of a layer each local window covers.
#include <cstddef>
#include <vector>

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
// window j, anchored at frame j * stride.
std::vector<Window> planWindows(std::size_t frames, int window, int stride);

}  // namespace hba::pyramid
