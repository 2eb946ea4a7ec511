#pragma once
// A closed planar curve sampled densely and walked by arc length, so that a
// vehicle driving it at constant speed advances equal distances per frame.
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace hba::sim {

class ClosedCurve {
 public:
  // `point(u)` for u in [0, 1) traces the curve once; sampled `samples` times.
  ClosedCurve(const std::function<Eigen::Vector2d(double)>& point, int samples = 20000);

  double perimeter() const { return cumulative_.back(); }
  // Position at arc length s (wraps around: laps repeat the same path).
  Eigen::Vector2d at(double s) const;

 private:
  std::vector<Eigen::Vector2d> points_;  // closed: last == first
  std::vector<double> cumulative_;       // arc length at each point
};

}  // namespace hba::sim
