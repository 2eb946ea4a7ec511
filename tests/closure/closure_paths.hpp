#pragma once
// Planar test paths for the closure stage: a true circle that returns to its
// start, and odometry that drifts along it.
#include <cmath>
#include <random>
#include <vector>

#include "hba/core/lie.hpp"
#include "hba/core/pose.hpp"

namespace hba::closure::test {

// `laps` times round a circle of `radius` m, `frames` poses, heading along it.
inline std::vector<Pose> circle(std::size_t frames, double radius, double laps = 1.0) {
  std::vector<Pose> poses;
  for (std::size_t k = 0; k < frames; ++k) {
    const double a = 2.0 * M_PI * laps * static_cast<double>(k) / static_cast<double>(frames - 1);
    poses.emplace_back(Mat3(Eigen::AngleAxisd(a + M_PI / 2, Vec3::UnitZ())),
                       Vec3(radius * std::cos(a), radius * std::sin(a), 0.0));
  }
  return poses;
}

// The truth's steps with a constant heading bias and random step errors,
// re-integrated from the first pose (kept exact).
inline std::vector<Pose> drifted(const std::vector<Pose>& truth, double yaw_bias_deg_per_step,
                                 double step_sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, step_sigma);
  std::vector<Pose> out{truth.front()};
  const Pose bias(Mat3(Eigen::AngleAxisd(yaw_bias_deg_per_step * M_PI / 180.0, Vec3::UnitZ())), Vec3::Zero());
  for (std::size_t k = 1; k < truth.size(); ++k) {
    Pose step = relative(truth[k - 1], truth[k]) * bias;
    step.t += Vec3(noise(rng), noise(rng), 0.1 * noise(rng));
    out.push_back(out.back() * step);
  }
  return out;
}

inline double largestError(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, (a[k].t - b[k].t).norm());
  return worst;
}

}  // namespace hba::closure::test
