#include "cell_assignment.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "hba/voxel/voxel_key.hpp"

namespace hba::voxel {
namespace {

// Points in runs along scan-like lines (neighbours mostly share a cell),
// either side of zero and far from the origin.
std::vector<Vec3f> scanLikePoints(std::mt19937& rng, const Vec3f& centre, float extent, int count) {
  std::uniform_real_distribution<float> u(-extent, extent);
  std::vector<Vec3f> points;
  Vec3f p = centre;
  for (int k = 0; k < count; ++k) {
    if (k % 50 == 0) p = centre + Vec3f(u(rng), u(rng), u(rng));
    p += Vec3f(0.03f, 0.01f * u(rng) / extent, 0.0f);
    points.push_back(p);
  }
  return points;
}

void expectSameAssignment(const CellAssignment& a, const CellAssignment& b) {
  EXPECT_EQ(a.cell_of_point, b.cell_of_point);
  EXPECT_EQ(a.first_point_of_cell, b.first_point_of_cell);
}

TEST(CellAssignment, CoarseCellsGatheredFromFineOnesAreTheCoarseAssignment) {
  std::mt19937 rng(3);
  for (const Vec3f& centre :
       {Vec3f(0.0f, 0.0f, 0.0f), Vec3f(-3.3f, 7.1f, -0.4f), Vec3f(512345.0f, -4321.0f, 88.0f)}) {
    const std::vector<Vec3f> points = scanLikePoints(rng, centre, 20.0f, 20000);
    for (const auto& [fine, coarse] : {std::pair{1.0, 2.0}, {1.0, 4.0}, {0.5, 4.0}, {0.25, 0.25}}) {
      const std::optional<CellAssignment> gathered = coarsenCells(assignCells(points, fine), points, coarse);
      ASSERT_TRUE(gathered.has_value()) << fine << " -> " << coarse;
      expectSameAssignment(*gathered, assignCells(points, coarse));
    }
  }
}

TEST(CellAssignment, CoarseningAtAnyRatioIsExactOrDeclined) {
  std::mt19937 rng(5);
  const std::vector<Vec3f> points = scanLikePoints(rng, Vec3f(10.0f, -20.0f, 1.0f), 30.0f, 20000);
  // 0.3 m cells inside 0.9 m ones: rounding may put a point in another coarse
  // cell than its fine cell's; then nothing is returned.
  for (const double coarse : {0.9, 1.2, 3.0}) {
    const std::optional<CellAssignment> gathered = coarsenCells(assignCells(points, 0.3), points, coarse);
    if (gathered) expectSameAssignment(*gathered, assignCells(points, coarse));
  }
  // Cells that do not nest at all (0.3 m inside 0.5 m) are declined.
  EXPECT_FALSE(coarsenCells(assignCells(points, 0.3), points, 0.5).has_value());
}

// First-hit numbering by its definition, one point after another.
CellAssignment numberedOneByOne(const std::vector<Vec3f>& points, double size) {
  std::map<VoxelKey, std::uint32_t> cell_of_key;
  CellAssignment out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const VoxelKey key = VoxelKey::of(points[i].cast<double>(), size);
    const auto [it, added] = cell_of_key.emplace(key, static_cast<std::uint32_t>(cell_of_key.size()));
    if (added) out.first_point_of_cell.push_back(static_cast<std::uint32_t>(i));
    out.cell_of_point.push_back(it->second);
  }
  return out;
}

// Clouds whose box holds few cells a point (a window at 1 m) are numbered
// in a grid over the box, others in a hash table: both in first-hit order,
// near the origin, either side of zero and far from it.
TEST(CellAssignment, SmallCloudsNumberCellsInFirstHitOrderInAGridOrATable) {
  std::mt19937 rng(4);
  for (const Vec3f& centre :
       {Vec3f(0.0f, 0.0f, 0.0f), Vec3f(-3.3f, 7.1f, -0.4f), Vec3f(512345.0f, -4321.0f, 88.0f)}) {
    // 20 000 points: a box of 10 m at 1 m is a grid (a few thousand
    // cells), at 0.1 m and across 2 km a table.
    for (const auto& [extent, size] : {std::pair{5.0f, 1.0}, {5.0f, 0.5}, {5.0f, 0.1}, {1000.0f, 1.0}}) {
      const std::vector<Vec3f> points = scanLikePoints(rng, centre, extent, 20000);
      expectSameAssignment(assignCells(points, size), numberedOneByOne(points, size));
    }
  }
}

// Clouds of millions (refinement blocks: keys taken in parallel) number
// their cells in first-hit order, with packed and with full keys, for any
// thread count.
TEST(CellAssignment, LargeCloudsNumberCellsInFirstHitOrder) {
  std::mt19937 rng(8);
  std::vector<Vec3f> points;
  for (int part = 0; part < 6; ++part) {  // 6 x 400 000 points revisiting one area
    const std::vector<Vec3f> more = scanLikePoints(rng, Vec3f(100.0f, -50.0f, 2.0f), 40.0f, 400000);
    points.insert(points.end(), more.begin(), more.end());
  }
  for (const bool far : {false, true}) {
    // One point 3000 km away: keys too wide to pack into one word.
    if (far) points[1234567] = Vec3f(3.0e6f, 0.0f, 0.0f);
    for (const double size : {1.0, 0.25}) {
      const CellAssignment expected = numberedOneByOne(points, size);
      for (const int threads : {1, 2}) {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        expectSameAssignment(assignCells(points, size, 64), expected);
      }
      // Cut into as many ranges as the arena has threads, numbered side by side.
      for (const int threads : {3, 7}) {
        tbb::task_arena arena(threads);
        arena.execute([&] { expectSameAssignment(assignCells(points, size, 64), expected); });
      }
    }
  }
}

// Members by cell, as one pass in point order would list them: each cell's
// ids ascending, the cells in their numbers' order, for any range count.
TEST(CellAssignment, MembersOfLargeCloudsAscendWithinEachCell) {
  std::mt19937 rng(9);
  std::vector<Vec3f> points;
  for (int part = 0; part < 4; ++part) {
    const std::vector<Vec3f> more = scanLikePoints(rng, Vec3f(-20.0f, 30.0f, 1.0f), 25.0f, 400000);
    points.insert(points.end(), more.begin(), more.end());
  }
  const CellAssignment cells = assignCells(points, 0.5, 64);
  std::vector<std::vector<std::uint32_t>> expected(cells.cells());
  for (std::size_t i = 0; i < points.size(); ++i) {
    expected[cells.cell_of_point[i]].push_back(static_cast<std::uint32_t>(i));
  }
  for (const int threads : {1, 2, 5}) {
    tbb::task_arena arena(threads);
    const CellMembers members = arena.execute([&] { return membersOf(cells); });
    ASSERT_EQ(members.begin.size(), cells.cells() + 1);
    ASSERT_EQ(members.ids.size(), points.size());
    for (std::size_t c = 0; c < cells.cells(); ++c) {
      const std::vector<std::uint32_t> got(members.ids.begin() + members.begin[c],
                                           members.ids.begin() + members.begin[c + 1]);
      ASSERT_EQ(got, expected[c]) << "cell " << c << ", " << threads << " threads";
    }
  }
}

// Edges that are no power of two (0.1 m scan voxels) take each key from a
// product with the inverse edge, divided only near a cell's boundary: the
// keys of VoxelKey::of still, for points on and a few ulps either side of
// boundaries, near zero, far out and not finite.
TEST(CellAssignment, KeysMatchTheDivisionAtCellBoundaries) {
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> cell(-2000000, 2000000);
  for (const double size : {0.1, 0.3, 0.05, 1.0 / 3.0, 0.7, 2.5}) {
    std::vector<Vec3f> points;
    for (int k = 0; k < 20000; ++k) {
      const float boundary = static_cast<float>(cell(rng) % (k % 3 == 0 ? 50 : 2000000) * size);
      float v = boundary;
      for (int step = 0; step < k % 7; ++step) v = std::nextafter(v, k % 2 ? 1e30f : -1e30f);
      points.emplace_back(v, boundary, -v);
    }
    points.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.0f, 1.0f);
    points.emplace_back(std::numeric_limits<float>::infinity(), -1e30f, 1e-30f);
    expectSameAssignment(assignCells(points, size), numberedOneByOne(points, size));
  }
}

}  // namespace
}  // namespace hba::voxel
