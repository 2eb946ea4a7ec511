#include "occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "hba/voxel/key_table.hpp"

namespace hba::closure {
namespace {

std::int64_t cellKey(long ix, long iy) {
  return (static_cast<std::int64_t>(ix) << 32) ^ static_cast<std::int64_t>(static_cast<std::uint32_t>(iy));
}

// The shifts as whole cells, or nothing when one is not (within 1e-9 of a
// cell: steps built by repeated additions of the cell).
std::optional<std::vector<long>> wholeCells(const std::vector<double>& shifts, double cell) {
  std::vector<long> cells;
  for (const double s : shifts) {
    const double ratio = s / cell;
    const double whole = std::round(ratio);
    if (!(std::abs(ratio - whole) < 1e-9) || !(std::abs(whole) < 1e9)) return std::nullopt;
    cells.push_back(static_cast<long>(whole));
  }
  return cells;
}

// A point's cell along one axis when shifting it by whole cells moves the
// cell by as many: its position in cells is finite, not huge, and more than
// a millionth of a cell from an edge (rounding errs by far less).
std::optional<long> stableCell(double v, double cell) {
  const double r = v / cell;
  if (!(std::abs(r) < 1e9)) return std::nullopt;
  const double base = std::floor(r);
  const double fraction = r - base;
  if (fraction < 1e-6 || fraction > 1.0 - 1e-6) return std::nullopt;
  return static_cast<long>(base);
}

}  // namespace

long cellIndex(double v, double cell) { return static_cast<long>(std::floor(v / cell)); }

std::vector<ColumnStats> structureColumns(const PointCloud& cloud, double cell, double height) {
  // Columns numbered as first met, each summing its points in point order.
  voxel::KeyNumbers<std::uint64_t> numbers(cloud.size() / 16);
  std::vector<ColumnStats> columns;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 p = cloud.world(i);
    const long ix = cellIndex(p.x(), cell);
    const long iy = cellIndex(p.y(), cell);
    bool inserted = false;
    const std::uint32_t number = numbers.insert(static_cast<std::uint64_t>(cellKey(ix, iy)), inserted);
    if (inserted) {
      ColumnStats fresh;
      fresh.ix = ix;
      fresh.iy = iy;
      fresh.z_min = fresh.z_max = p.z();
      columns.push_back(fresh);
    }
    ColumnStats& c = columns[number];
    c.z_min = std::min(c.z_min, p.z());
    c.z_max = std::max(c.z_max, p.z());
    c.sum += p;
    ++c.count;
  }
  std::vector<ColumnStats> kept;
  for (const ColumnStats& c : columns) {
    if (c.z_max - c.z_min >= height) kept.push_back(c);
  }
  std::sort(kept.begin(), kept.end(), [](const ColumnStats& a, const ColumnStats& b) {
    return cellKey(a.ix, a.iy) < cellKey(b.ix, b.iy);
  });
  return kept;
}

OccupancyGrid::OccupancyGrid(const std::vector<ColumnStats>& columns, double cell, int dilation)
    : cell_(cell) {
  if (columns.empty()) return;
  min_x_ = max_x_ = columns.front().ix;
  min_y_ = max_y_ = columns.front().iy;
  for (const ColumnStats& c : columns) {
    min_x_ = std::min(min_x_, c.ix);
    max_x_ = std::max(max_x_, c.ix);
    min_y_ = std::min(min_y_, c.iy);
    max_y_ = std::max(max_y_, c.iy);
  }
  min_x_ -= dilation;
  min_y_ -= dilation;
  max_x_ += dilation;
  max_y_ += dilation;
  width_ = max_x_ - min_x_ + 1;
  occupied_.assign(static_cast<std::size_t>(width_ * (max_y_ - min_y_ + 1)), 0);
  for (const ColumnStats& c : columns) {
    for (long dx = -dilation; dx <= dilation; ++dx) {
      for (long dy = -dilation; dy <= dilation; ++dy) occupied_[index(c.ix + dx, c.iy + dy)] = 1;
    }
  }
}

bool OccupancyGrid::occupied(const Vec2& p) const {
  if (occupied_.empty()) return false;
  return occupiedCell(cellIndex(p.x(), cell_), cellIndex(p.y(), cell_));
}

std::vector<std::uint32_t> countHits(const OccupancyGrid& grid, const std::vector<Vec2>& points,
                                     const std::vector<double>& xs, const std::vector<double>& ys) {
  const std::size_t nx = xs.size();
  const std::size_t ny = ys.size();
  // Counted row by row (shift j, then i: a point's shifts along x read one
  // grid row), handed out as hits[i * ny + j].
  std::vector<std::uint32_t> by_row(nx * ny, 0);
  const std::optional<std::vector<long>> cx = wholeCells(xs, grid.cell());
  const std::optional<std::vector<long>> cy = wholeCells(ys, grid.cell());
  // A point shifted as a point: its cells along each axis, taken once.
  std::vector<long> shifted_x(nx), shifted_y(ny);
  for (const Vec2& p : points) {
    const std::optional<long> ix = cx && cy ? stableCell(p.x(), grid.cell()) : std::nullopt;
    const std::optional<long> iy = ix ? stableCell(p.y(), grid.cell()) : std::nullopt;
    if (!iy) {  // shifted as a point, as the definition says: p + (xs[i], ys[j]) per axis
      for (std::size_t i = 0; i < nx; ++i) shifted_x[i] = cellIndex(p.x() + xs[i], grid.cell());
      for (std::size_t j = 0; j < ny; ++j) shifted_y[j] = cellIndex(p.y() + ys[j], grid.cell());
    } else {
      for (std::size_t i = 0; i < nx; ++i) shifted_x[i] = *ix + (*cx)[i];
      for (std::size_t j = 0; j < ny; ++j) shifted_y[j] = *iy + (*cy)[j];
    }
    for (std::size_t j = 0; j < ny; ++j) {
      const std::uint8_t* row = grid.row(shifted_y[j]);
      if (row == nullptr) continue;
      std::uint32_t* counts = by_row.data() + j * nx;
      for (std::size_t i = 0; i < nx; ++i) {
        const long x = shifted_x[i];
        if (x >= grid.firstColumn() && x <= grid.lastColumn()) counts[i] += row[x - grid.firstColumn()];
      }
    }
  }
  std::vector<std::uint32_t> hits(nx * ny);
  for (std::size_t j = 0; j < ny; ++j) {
    for (std::size_t i = 0; i < nx; ++i) hits[i * ny + j] = by_row[j * nx + i];
  }
  return hits;
}

}  // namespace hba::closure
