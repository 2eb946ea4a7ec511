#pragma once
// Wall-clock durations in seconds, for the timings that reports and logs give.
#include <chrono>

namespace hba {

using Clock = std::chrono::steady_clock;

inline double secondsBetween(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double>(end - start).count();
}

inline double secondsSince(Clock::time_point start) { return secondsBetween(start, Clock::now()); }

}  // namespace hba
