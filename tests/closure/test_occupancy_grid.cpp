// The bird's-eye search's hit counts: the same as shifting every point and
// looking its cell up, also for points on and next to cell edges, far from
// the origin, and for shifts that are not whole cells.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "occupancy_grid.hpp"

namespace hba::closure {
namespace {

std::vector<std::uint32_t> byDefinition(const OccupancyGrid& grid, const std::vector<Vec2>& points,
                                        const std::vector<double>& xs, const std::vector<double>& ys) {
  std::vector<std::uint32_t> hits(xs.size() * ys.size(), 0);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (std::size_t j = 0; j < ys.size(); ++j) {
      for (const Vec2& p : points) hits[i * ys.size() + j] += grid.occupied(p + Vec2(xs[i], ys[j]));
    }
  }
  return hits;
}

// Random structure columns around `centre` (metres), the grid made of them.
std::vector<ColumnStats> randomColumns(const Vec2& centre, double cell, std::mt19937& random) {
  std::uniform_real_distribution<double> spread(-15.0, 15.0);
  std::vector<ColumnStats> columns;
  for (int k = 0; k < 300; ++k) {
    ColumnStats c;
    c.ix = cellIndex(centre.x() + spread(random), cell);
    c.iy = cellIndex(centre.y() + spread(random), cell);
    columns.push_back(c);
  }
  return columns;
}

// Shifts centre + k * step as the search builds them.
std::vector<double> shifts(double centre, int n, double step) {
  std::vector<double> out;
  for (int k = -n; k <= n; ++k) out.push_back(centre + static_cast<double>(k) * step);
  return out;
}

TEST(OccupancyGrid, HitCountsMatchTheDefinition) {
  std::mt19937 random(3);
  const double cell = 0.5;
  for (const Vec2& centre : {Vec2(0.0, 0.0), Vec2(3.2e5, -4.1e6)}) {  // near the origin, and UTM
    for (const int dilation : {0, 1}) {
      const OccupancyGrid grid(randomColumns(centre, cell, random), cell, dilation);
      std::uniform_real_distribution<double> spread(-20.0, 20.0);
      std::vector<Vec2> points;
      for (int k = 0; k < 400; ++k) {
        Vec2 p = centre + Vec2(spread(random), spread(random));
        if (k % 4 == 0) p.x() = cell * std::round(p.x() / cell);                          // on an edge
        if (k % 4 == 1) p.y() = std::nextafter(cell * std::round(p.y() / cell), -1e300);  // just below one
        if (k % 4 == 2) p.x() = cell * std::round(p.x() / cell) + 1e-8;  // within the guard band
        points.push_back(p);
      }
      points.push_back(Vec2(std::nan(""), 0.0));
      // Whole cells (both levels' shifts, centred on a peak or not), and not.
      for (const auto& [xs, ys] : {std::pair{shifts(0.0, 8, cell), shifts(0.0, 8, cell)},
                                   std::pair{shifts(4 * cell * 3, 4, cell), shifts(-4 * cell * 2, 4, cell)},
                                   std::pair{shifts(0.25, 3, 0.25 * cell), shifts(0.0, 3, 0.25 * cell)}}) {
        ASSERT_EQ(countHits(grid, points, xs, ys), byDefinition(grid, points, xs, ys));
      }
    }
  }
}

TEST(OccupancyGrid, AnEmptyGridHitsNothing) {
  const OccupancyGrid grid({}, 0.5, 1);
  const std::vector<std::uint32_t> hits =
      countHits(grid, {Vec2(0.1, 0.2), Vec2(5.0, 5.0)}, shifts(0.0, 2, 0.5), shifts(0.0, 2, 0.5));
  EXPECT_EQ(hits, std::vector<std::uint32_t>(25, 0));
}

}  // namespace
}  // namespace hba::closure
