#include "closed_curve.hpp"

#include <algorithm>
#include <cmath>

namespace hba::sim {

ClosedCurve::ClosedCurve(const std::function<Eigen::Vector2d(double)>& point, int samples) {
  points_.reserve(samples + 1);
  cumulative_.reserve(samples + 1);
  for (int i = 0; i <= samples; ++i) {
    points_.push_back(point(static_cast<double>(i % samples) / samples));
    cumulative_.push_back(i == 0 ? 0.0 : cumulative_.back() + (points_[i] - points_[i - 1]).norm());
  }
}

Eigen::Vector2d ClosedCurve::at(double s) const {
  s = std::fmod(s, perimeter());
  if (s < 0.0) s += perimeter();
  const auto upper = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const auto i = static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(upper - cumulative_.begin(), 1, cumulative_.size() - 1));
  const double span = cumulative_[i] - cumulative_[i - 1];
  const double f = span > 0.0 ? (s - cumulative_[i - 1]) / span : 0.0;
  return points_[i - 1] + f * (points_[i] - points_[i - 1]);
}

}  // namespace hba::sim
