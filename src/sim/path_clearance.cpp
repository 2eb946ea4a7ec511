#include "path_clearance.hpp"

#include <algorithm>
#include <cmath>

namespace hba::sim {
namespace {

constexpr double kSampleSpacing = 0.5;
// A jump this long between consecutive poses is a gap in the data, not a road.
constexpr double kMaxBridgedGap = 20.0;

struct PathSample {
  Eigen::Vector2d xy;
  double heading;
};

std::vector<PathSample> densify(const std::vector<Pose>& path) {
  std::vector<PathSample> samples;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const Eigen::Vector2d p = path[k].t.head<2>();
    const Vec3 forward = path[k].R().col(0);
    const double heading = std::atan2(forward.y(), forward.x());
    if (k > 0) {
      const Eigen::Vector2d previous = path[k - 1].t.head<2>();
      const double gap = (p - previous).norm();
      if (gap < kMaxBridgedGap) {
        const int steps = static_cast<int>(gap / kSampleSpacing);
        for (int i = 1; i <= steps; ++i) {
          samples.push_back({previous + (p - previous) * (i * kSampleSpacing / gap), heading});
        }
      }
    }
    samples.push_back({p, heading});
  }
  return samples;
}

}  // namespace

PathClearance::PathClearance(const std::vector<Pose>& path, double reach, double margin, double cell)
    : cell_(cell), reach_(reach) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const Pose& pose : path) {
    lo = lo.cwiseMin(pose.t.head<2>());
    hi = hi.cwiseMax(pose.t.head<2>());
  }
  origin_ = lo - Eigen::Vector2d::Constant(margin);
  columns_ = static_cast<std::size_t>(std::ceil((hi.x() - lo.x() + 2 * margin) / cell)) + 1;
  rows_ = static_cast<std::size_t>(std::ceil((hi.y() - lo.y() + 2 * margin) / cell)) + 1;
  distance_.assign(columns_ * rows_, static_cast<float>(reach));
  heading_.assign(columns_ * rows_, 0.0f);

  const int radius = static_cast<int>(std::ceil(reach / cell));
  for (const PathSample& sample : densify(path)) {
    const int cx = static_cast<int>((sample.xy.x() - origin_.x()) / cell);
    const int cy = static_cast<int>((sample.xy.y() - origin_.y()) / cell);
    for (int y = std::max(0, cy - radius); y <= std::min<int>(rows_ - 1, cy + radius); ++y) {
      for (int x = std::max(0, cx - radius); x <= std::min<int>(columns_ - 1, cx + radius); ++x) {
        const Eigen::Vector2d center = origin_ + cell * Eigen::Vector2d(x + 0.5, y + 0.5);
        const auto d = static_cast<float>((center - sample.xy).norm());
        const std::size_t i = static_cast<std::size_t>(y) * columns_ + x;
        if (d < distance_[i]) {
          distance_[i] = d;
          heading_[i] = static_cast<float>(sample.heading);
        }
      }
    }
  }
}

bool PathClearance::index(double x, double y, std::size_t& out) const {
  const double fx = (x - origin_.x()) / cell_;
  const double fy = (y - origin_.y()) / cell_;
  if (fx < 0 || fy < 0 || fx >= static_cast<double>(columns_) || fy >= static_cast<double>(rows_)) {
    return false;
  }
  out = static_cast<std::size_t>(fy) * columns_ + static_cast<std::size_t>(fx);
  return true;
}

double PathClearance::clearance(double x, double y) const {
  std::size_t i = 0;
  return index(x, y, i) ? distance_[i] : reach_;
}

double PathClearance::heading(double x, double y) const {
  std::size_t i = 0;
  return index(x, y, i) ? heading_[i] : 0.0;
}

Eigen::Vector2d PathClearance::maxCorner() const {
  return origin_ + cell_ * Eigen::Vector2d(static_cast<double>(columns_), static_cast<double>(rows_));
}

std::vector<Eigen::Vector2d> PathClearance::cellsBetween(double near, double far) const {
  std::vector<Eigen::Vector2d> cells;
  for (std::size_t y = 0; y < rows_; ++y) {
    for (std::size_t x = 0; x < columns_; ++x) {
      const float d = distance_[y * columns_ + x];
      if (d >= near && d <= far) {
        cells.push_back(origin_ + cell_ * Eigen::Vector2d(x + 0.5, y + 0.5));
      }
    }
  }
  return cells;
}

}  // namespace hba::sim
