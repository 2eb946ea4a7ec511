#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "core/kd_tree.hpp"

namespace hba {
namespace {

template <int Dim>
std::vector<Eigen::Matrix<float, Dim, 1>> randomItems(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coordinate(-5.0F, 5.0F);
  std::vector<Eigen::Matrix<float, Dim, 1>> items(count);
  for (auto& item : items)
    for (int d = 0; d < Dim; ++d) item[d] = coordinate(rng);
  return items;
}

template <int Dim>
float bruteNearestSq(const std::vector<Eigen::Matrix<float, Dim, 1>>& items,
                     const Eigen::Matrix<float, Dim, 1>& q) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& item : items) best = std::min(best, (item - q).squaredNorm());
  return best;
}

// The nearest item is the one a scan of every item finds, in 3-D and in the
// 33-D of the closure's descriptors.
TEST(KdTree, NearestIsTheNearestOfAllItems) {
  const auto points = randomItems<3>(2000, 1);
  const KdTree<3> tree(points);
  const auto descriptors = randomItems<33>(500, 2);
  const KdTree<33> descriptor_tree(descriptors);
  const auto queries = randomItems<3>(200, 3);
  const auto descriptor_queries = randomItems<33>(50, 4);
  for (const auto& q : queries) {
    const auto [index, distance_sq] = tree.nearest(q);
    ASSERT_LT(index, points.size());
    EXPECT_FLOAT_EQ(distance_sq, (points[index] - q).squaredNorm());
    EXPECT_FLOAT_EQ(distance_sq, bruteNearestSq(points, q));
  }
  for (const auto& q : descriptor_queries)
    EXPECT_FLOAT_EQ(descriptor_tree.nearest(q).second, bruteNearestSq(descriptors, q));
}

// An approximate search returns an item at most (1 + eps) times the nearest
// squared distance away.
TEST(KdTree, ApproximateNearestIsWithinItsBound) {
  const auto descriptors = randomItems<33>(1000, 5);
  const KdTree<33> tree(descriptors);
  const float eps = 0.5F;
  for (const auto& q : randomItems<33>(50, 6)) {
    const auto [index, distance_sq] = tree.nearest(q, eps);
    ASSERT_LT(index, descriptors.size());
    EXPECT_LE(distance_sq, (1.0F + eps) * bruteNearestSq(descriptors, q) * 1.0001F);
  }
}

// `within` returns exactly the items strictly inside the radius, with their
// squared distances.
TEST(KdTree, WithinReturnsExactlyTheItemsInsideTheRadius) {
  const auto points = randomItems<3>(3000, 7);
  const KdTree<3> tree(points, /*leaf_size=*/16);
  const float radius = 1.2F;
  for (const auto& q : randomItems<3>(100, 8)) {
    auto found = tree.within(q, radius);
    std::vector<std::uint32_t> indices;
    for (const auto& [i, d_sq] : found) {
      EXPECT_FLOAT_EQ(d_sq, (points[i] - q).squaredNorm());
      indices.push_back(i);
    }
    std::sort(indices.begin(), indices.end());
    std::vector<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < points.size(); ++i)
      if ((points[i] - q).squaredNorm() < radius * radius) expected.push_back(i);
    EXPECT_EQ(indices, expected);
    EXPECT_FALSE(expected.empty());
  }
}

// A visitor of our own (as the map entropy's moment collector) sees every
// item the radius holds.
struct CountingVisitor {
  using DistanceType = float;
  using IndexType = std::uint32_t;
  float radius_sq;
  std::size_t count = 0;
  bool full() const { return true; }
  float worstDist() const { return radius_sq; }
  void sort() {}
  bool addPoint(float distance_sq, std::uint32_t) {
    if (distance_sq < radius_sq) ++count;
    return true;
  }
};

TEST(KdTree, VisitorSeesEveryItemInsideTheRadius) {
  const auto points = randomItems<3>(1000, 9);
  const KdTree<3> tree(points);
  const Eigen::Vector3f q(0.5F, -0.5F, 1.0F);
  CountingVisitor visitor{4.0F};
  tree.visit(visitor, q);
  const auto inside = std::count_if(points.begin(), points.end(),
                                    [&](const Eigen::Vector3f& p) { return (p - q).squaredNorm() < 4.0F; });
  EXPECT_EQ(visitor.count, static_cast<std::size_t>(inside));
  EXPECT_GT(visitor.count, 0U);
}

TEST(KdTree, EmptyTreeFindsNothing) {
  const std::vector<Eigen::Vector3f> none;
  const KdTree<3> tree(none);
  EXPECT_EQ(tree.nearest(Eigen::Vector3f::Zero()).first, 0U);
  EXPECT_TRUE(tree.within(Eigen::Vector3f::Zero(), 10.0F).empty());
  CountingVisitor visitor{100.0F};
  tree.visit(visitor, Eigen::Vector3f::Zero());
  EXPECT_EQ(visitor.count, 0U);
}

}  // namespace
}  // namespace hba
