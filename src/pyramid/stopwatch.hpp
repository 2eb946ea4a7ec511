#pragma once
// Wall-clock timing of the pyramid's stages (for the report).
#include <chrono>

namespace hba::pyramid {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace hba::pyramid
