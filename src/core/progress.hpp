#pragma once
// Progress of long work (windows of a layer, rounds of the refinement) for
// whoever shows it: the library counts, the application draws (a bar on a
// terminal, plain periodic lines in a log). Without a sink, counting is all
// it costs. Thread-safe: windows finish on many threads.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

namespace hba {

struct ProgressState {
  std::string label;  // "layer 1", "refinement"
  std::string unit;   // "windows", "rounds"
  std::size_t done = 0;
  std::size_t total = 0;
  double seconds = 0.0;  // since the start
  bool finished = false;
  // Units per second so far, and the seconds left at that rate (-1: unknown).
  double rate() const { return seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0; }
  double secondsLeft() const {
    return done == 0 || total < done ? -1.0 : static_cast<double>(total - done) / rate();
  }
};

using ProgressSink = std::function<void(const ProgressState&)>;
// The application's sink; called at most every 0.1 s per task, and once finished.
void setProgressSink(ProgressSink sink);

class Progress {
 public:
  Progress(std::string label, std::size_t total, std::string unit);
  ~Progress();  // reports the finish
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void advance(std::size_t count = 1);

 private:
  void report(bool finished);
  std::string label_, unit_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  // Nanoseconds from start_ to the last report: read by every advance()
  // without the lock, so atomic.
  std::atomic<std::int64_t> last_report_ns_{0};
  std::mutex mutex_;
};

// "1:05", "12 s", "2:03:10"
std::string formatDuration(double seconds);

}  // namespace hba
