// The bird's-eye search's hit counts: the same as shifting every point and
// looking its cell up, also for points on and next to cell edges, far from
// the origin, and for shifts that are not whole cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>

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
      // Whole cells (both levels' shifts, centred on a peak or not; two
      // cells apart), and not.
      for (const auto& [xs, ys] : {std::pair{shifts(0.0, 8, cell), shifts(0.0, 8, cell)},
                                   std::pair{shifts(4 * cell * 3, 4, cell), shifts(-4 * cell * 2, 4, cell)},
                                   std::pair{shifts(0.0, 5, 2 * cell), shifts(cell, 3, cell)},
                                   std::pair{shifts(60.0, 2, cell), shifts(0.0, 2, cell)},  // off the grid
                                   std::pair{shifts(0.25, 3, 0.25 * cell), shifts(0.0, 3, 0.25 * cell)}}) {
        ASSERT_EQ(countHits(grid, points, xs, ys), byDefinition(grid, points, xs, ys));
      }
    }
  }
}

// Columns by definition: every point's column in an ordered map, its
// points summed in point order; kept where they span `height`.
std::vector<ColumnStats> columnsByDefinition(const PointCloud& cloud, double cell, double height) {
  std::map<std::pair<long, long>, ColumnStats> columns;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 p = cloud.world(i);
    const long ix = cellIndex(p.x(), cell);
    const long iy = cellIndex(p.y(), cell);
    auto [it, fresh] = columns.try_emplace({ix, iy});
    ColumnStats& c = it->second;
    if (fresh) {
      c.ix = ix;
      c.iy = iy;
      c.z_min = c.z_max = p.z();
    }
    c.z_min = std::min(c.z_min, p.z());
    c.z_max = std::max(c.z_max, p.z());
    c.sum += p;
    ++c.count;
  }
  std::vector<ColumnStats> kept;
  for (const auto& [key, c] : columns) {
    if (c.z_max - c.z_min >= height) kept.push_back(c);
  }
  return kept;
}

TEST(OccupancyGrid, StructureColumnsAreThoseOfTheDefinitionToTheBit) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> spread(-30.0, 30.0);
  std::uniform_real_distribution<double> height(-1.0, 3.0);
  for (const Vec3& origin : {Vec3(0.0, 0.0, 0.0), Vec3(3.2e5, -4.1e6, 80.0)}) {  // and UTM
    PointCloud cloud;
    cloud.origin = origin;
    for (int k = 0; k < 20000; ++k) {
      // Mostly ground, some walls: columns of both kinds, many points each.
      const bool wall = k % 5 == 0;
      cloud.points.emplace_back(static_cast<float>(spread(random)), static_cast<float>(spread(random)),
                                static_cast<float>(wall ? height(random) : 0.05 * height(random)));
    }
    for (const double cell : {0.25, 0.5, 2.0}) {
      // Compared column by column in (ix, iy) order (the search keeps its own fixed order).
      std::vector<ColumnStats> found = structureColumns(cloud, cell, 0.5);
      std::sort(found.begin(), found.end(), [](const ColumnStats& a, const ColumnStats& b) {
        return std::pair(a.ix, a.iy) < std::pair(b.ix, b.iy);
      });
      const std::vector<ColumnStats> expected = columnsByDefinition(cloud, cell, 0.5);
      ASSERT_EQ(found.size(), expected.size());
      ASSERT_GT(found.size(), 10u);
      ASSERT_LT(found.size(), columnsByDefinition(cloud, cell, 0.0).size());  // some are ground only
      for (std::size_t c = 0; c < found.size(); ++c) {
        EXPECT_EQ(found[c].ix, expected[c].ix);
        EXPECT_EQ(found[c].iy, expected[c].iy);
        EXPECT_EQ(found[c].z_min, expected[c].z_min);
        EXPECT_EQ(found[c].z_max, expected[c].z_max);
        EXPECT_EQ(found[c].count, expected[c].count);
        EXPECT_TRUE(found[c].sum == expected[c].sum) << "column " << c;
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
