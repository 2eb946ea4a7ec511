#include "window_batches.hpp"

#include <algorithm>

namespace hba::pyramid {

std::size_t windowsPerBatch(bool scans, std::size_t threads) {
  const std::size_t per_thread = scans ? 4 : 1;
  return per_thread * std::max<std::size_t>(threads, 1);
}

std::vector<WindowBatch> batchWindows(const std::vector<Window>& windows, std::size_t windows_per_batch) {
  const std::size_t size = std::max<std::size_t>(windows_per_batch, 1);
  std::vector<WindowBatch> batches;
  for (std::size_t b0 = 0; b0 < windows.size(); b0 += size) {
    WindowBatch batch;
    batch.first_window = b0;
    batch.end_window = std::min(windows.size(), b0 + size);
    batch.first_frame = windows[b0].first;
    batch.end_frame = windows[b0].first + windows[b0].count;
    for (std::size_t w = b0; w < batch.end_window; ++w) {
      batch.first_frame = std::min(batch.first_frame, windows[w].first);
      batch.end_frame = std::max(batch.end_frame, windows[w].first + windows[w].count);
    }
    batches.push_back(batch);
  }
  return batches;
}

}  // namespace hba::pyramid
