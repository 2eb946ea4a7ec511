#include "core/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hba {
namespace {

constexpr std::int64_t kReportEveryNs = 100'000'000;  // at most ten reports a second

std::mutex& sinkMutex() {
  static std::mutex mutex;
  return mutex;
}

ProgressSink& sink() {
  static ProgressSink instance;
  return instance;
}

}  // namespace

void setProgressSink(ProgressSink new_sink) {
  const std::lock_guard<std::mutex> lock(sinkMutex());
  sink() = std::move(new_sink);
}

Progress::Progress(std::string label, std::size_t total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total) {}

Progress::~Progress() { report(true); }

void Progress::advance(std::size_t count) {
  done_ += count;
  const std::int64_t now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
  if (now_ns - last_report_ns_.load(std::memory_order_relaxed) < kReportEveryNs) return;  // cheap check
  report(false);
}

void Progress::report(bool finished) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - start_).count();
  if (!finished && now_ns - last_report_ns_.load() < kReportEveryNs) return;
  last_report_ns_.store(now_ns);
  ProgressState state;
  state.label = label_;
  state.unit = unit_;
  state.done = done_.load();
  state.total = total_;
  state.seconds = std::chrono::duration<double>(now - start_).count();
  state.finished = finished;
  const std::lock_guard<std::mutex> sink_lock(sinkMutex());
  if (sink()) sink()(state);
}

std::string formatDuration(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  char text[32];
  if (total < 60) {
    std::snprintf(text, sizeof(text), "%ld s", total);
  } else if (total < 3600) {
    std::snprintf(text, sizeof(text), "%ld:%02ld", total / 60, total % 60);
  } else {
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  }
  return text;
}

}  // namespace hba
