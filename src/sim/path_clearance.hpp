#pragma once
// A 2-D raster around a path that answers "how far is (x, y) from the path,
// and which way does the path run there" in O(1), for placing objects
// outside the free corridor.
#include <cstdint>
#include <vector>

#include "hba/core/pose.hpp"

namespace hba::sim {

class PathClearance {
 public:
  // Distances are exact to the path's samples (densified to every 0.5 m),
  // up to `reach`; farther cells read as `reach`. `margin` pads the path's box.
  PathClearance(const std::vector<Pose>& path, double reach, double margin, double cell = 1.0);

  double clearance(double x, double y) const;
  // Heading (rad) of the nearest path sample.
  double heading(double x, double y) const;

  Eigen::Vector2d minCorner() const { return origin_; }
  Eigen::Vector2d maxCorner() const;
  double cell() const { return cell_; }
  // Centers of the cells whose clearance is within [near, far].
  std::vector<Eigen::Vector2d> cellsBetween(double near, double far) const;

 private:
  bool index(double x, double y, std::size_t& out) const;

  Eigen::Vector2d origin_;
  double cell_;
  double reach_;
  std::size_t columns_ = 0, rows_ = 0;
  std::vector<float> distance_;
  std::vector<float> heading_;
};

}  // namespace hba::sim
