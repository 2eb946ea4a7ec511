#pragma once
// What every harness checks of a parser's result (shared by harness_*.cpp):
// bad input may only be refused with hba::Error, and what is returned keeps
// the reader's promises. A broken promise aborts, so the fuzzer reports it.
#include <cmath>
#include <cstdlib>

#include "hba/core/error.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::fuzz {

template <typename Parse>
void rejectOnlyWithError(Parse parse) {
  try {
    parse();
  } catch (const Error&) {
    // The documented outcome for bad input.
  }
}

// The readers drop NaN/Inf points and keep intensity and time one per point.
inline void checkCloud(const PointCloud& cloud) {
  if (cloud.hasIntensity() && cloud.intensity.size() != cloud.size()) std::abort();
  if (!cloud.time.empty() && cloud.time.size() != cloud.size()) std::abort();
  for (const Vec3f& p : cloud.points) {
    if (!p.allFinite()) std::abort();
  }
}

// A rotation read from a file is a unit quaternion.
inline void checkRotation(const Quat& q) {
  if (!q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-6) std::abort();
}

}  // namespace hba::fuzz
