#include "scan_writer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <mutex>

#include "core/progress.hpp"
#include "hba/io/pcd.hpp"

namespace hba::sim {
namespace fs = std::filesystem;

void writeScans(std::size_t frames, const std::function<PointCloud(std::size_t)>& scan_frame,
                const fs::path& scans, const WriteOptions& options) {
  fs::create_directory(scans);
  std::atomic<std::size_t> done{0};
  Progress progress("simulating", frames, "frames");
  std::mutex progress_mutex;
  // One frame per task: frames cost milliseconds each, so scheduling is free,
  // and each frame's output depends only on (seed, frame).
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, frames, 1), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          io::writePcd(scans / scanFileName(k, frames), scan_frame(k), io::PcdEncoding::Binary);
          const std::size_t finished = ++done;
          progress.advance();
          const bool report =
              options.progress && options.progress_every > 0 && finished % options.progress_every == 0;
          if (report) {
            const std::lock_guard<std::mutex> lock(progress_mutex);
            options.progress(finished, frames);
          }
        }
      });
  if (options.progress && (options.progress_every == 0 || frames % options.progress_every != 0)) {
    options.progress(frames, frames);
  }
}

}  // namespace hba::sim
