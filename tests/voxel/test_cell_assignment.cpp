#include "cell_assignment.hpp"

#include <gtest/gtest.h>

#include <random>

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

}  // namespace
}  // namespace hba::voxel
