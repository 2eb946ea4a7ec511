#pragma once
// Hand-made layers and window results for the pyramid's unit tests: uneven
// windows (no common stride) and poses that differ frame by frame, so that
// code assuming a uniform stride picks the wrong frames.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hba/core/lie.hpp"
#include "hba/core/pose.hpp"
#include "layer.hpp"

namespace hba::pyramid::test {

// A pose moved along x and turned about z.
inline Pose poseAt(double x, double y, double yaw_deg) {
  return Pose(so3Exp(Vec3(0.0, 0.0, yaw_deg * M_PI / 180.0)), Vec3(x, y, 0.0));
}

// 14 frames in three windows: own frames 0-2, 3-6 and 7-13.
inline std::vector<Window> unevenPlan() { return {Window{0, 6}, Window{3, 6}, Window{7, 7}}; }

// A window result whose poses differ from window to window and frame to frame.
inline WindowOutcome handMadeOutcome(const Window& window, std::size_t j) {
  WindowOutcome out;
  out.window = window;
  for (std::size_t k = 0; k < window.count; ++k) {
    const double jd = static_cast<double>(j);
    const double kd = static_cast<double>(k);
    out.optimized.push_back(poseAt(jd + 1.1 * kd, 0.2 * jd - 0.05 * kd * kd, 3.0 * jd + 2.0 * kd));
  }
  out.has_planes = true;
  return out;
}

inline LayerOutcome handMadeLayerOutcome(const std::vector<Window>& plan) {
  LayerOutcome outcome;
  for (std::size_t j = 0; j < plan.size(); ++j) outcome.windows.push_back(handMadeOutcome(plan[j], j));
  return outcome;
}

inline void expectNear(const Pose& a, const Pose& b, double tolerance = 1e-12) {
  EXPECT_LT((a.t - b.t).norm(), tolerance) << a.t.transpose() << " vs " << b.t.transpose();
  EXPECT_LT(a.q.angularDistance(b.q), tolerance);
}

}  // namespace hba::pyramid::test
