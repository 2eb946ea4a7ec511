#pragma once
#include <cstddef>
#include <vector>

#include "hba/pyramid/window_plan.hpp"

namespace hba::pyramid {

// Consecutive windows of a layer optimized together: the clouds of their
// frames are held at once, and nothing else, which bounds the memory.
struct WindowBatch {
  std::size_t first_window = 0;
  std::size_t end_window = 0;   // one past the last window
  std::size_t first_frame = 0;  // the frames the batch's windows cover
  std::size_t end_frame = 0;    // one past the last
};

// Windows per batch with `threads` threads. Layer-1 scans are small: several
// windows per thread keep the threads busy. Keyframes grow with the layer:
// one window per thread.
std::size_t windowsPerBatch(bool scans, std::size_t threads);

// The plan's windows, in order, in batches of `windows_per_batch` (the last
// may hold fewer).
std::vector<WindowBatch> batchWindows(const std::vector<Window>& windows, std::size_t windows_per_batch);

}  // namespace hba::pyramid
