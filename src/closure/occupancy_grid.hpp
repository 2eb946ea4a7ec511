#pragma once
// The bird's-eye search's grid (private to closure): the columns of a map
// whose points span some height (walls, poles, trunks), as a dense occupancy
// grid, and the score of a set of planar offsets: the share of query points
// that land on an occupied cell.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hba/core/point_cloud.hpp"

namespace hba::closure {

using Vec2 = Eigen::Vector2d;

struct ColumnStats {
  long ix = 0;
  long iy = 0;
  double z_min = 0.0;
  double z_max = 0.0;
  Vec3 sum = Vec3::Zero();
  std::size_t count = 0;
};

// The cell of v along one axis: floor(v / cell).
long cellIndex(double v, double cell);

// Columns (cells of the xy grid) whose points span at least `height`, in a
// fixed order (by key), each with the centroid of its points.
std::vector<ColumnStats> structureColumns(const PointCloud& cloud, double cell, double height);

class OccupancyGrid {
 public:
  // The columns' cells, each grown by `dilation` cells on every side.
  OccupancyGrid(const std::vector<ColumnStats>& columns, double cell, int dilation);

  double cell() const { return cell_; }
  bool occupied(const Vec2& p) const;
  // Whether cell (ix, iy) is occupied (false outside the grid).
  bool occupiedCell(long ix, long iy) const {
    if (ix < min_x_ || ix > max_x_ || iy < min_y_ || iy > max_y_) return false;
    return occupied_[index(ix, iy)] != 0;
  }
  // Row iy as flags (1 occupied) for the columns firstColumn() ..
  // lastColumn(), or null outside the grid.
  const std::uint8_t* row(long iy) const {
    if (iy < min_y_ || iy > max_y_) return nullptr;
    return occupied_.data() + index(min_x_, iy);
  }
  long firstColumn() const { return min_x_; }
  long lastColumn() const { return max_x_; }

 private:
  std::size_t index(long ix, long iy) const {
    return static_cast<std::size_t>((iy - min_y_) * width_ + (ix - min_x_));
  }

  double cell_;
  long min_x_ = 0, max_x_ = -1, min_y_ = 0, max_y_ = -1, width_ = 0;
  std::vector<std::uint8_t> occupied_;
};

// For every shift (xs[i], ys[j]), how many of `points` land on an occupied
// cell once shifted: hits[i * ys.size() + j]. Exactly
// sum_k grid.occupied(points[k] + (xs[i], ys[j])), but where the shifts are
// whole cells, each point's cell is found once and the shifts are cell
// offsets (a point within a millionth of a cell of an edge, where rounding
// could tell the two apart, is shifted as a point).
std::vector<std::uint32_t> countHits(const OccupancyGrid& grid, const std::vector<Vec2>& points,
                                     const std::vector<double>& xs, const std::vector<double>& ys);

}  // namespace hba::closure
