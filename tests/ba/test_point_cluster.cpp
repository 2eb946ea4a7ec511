#include <gtest/gtest.h>

#include <random>

#include "hba/ba/plane_cost.hpp"
#include "hba/core/point_cluster.hpp"

namespace hba::ba {
namespace {

TEST(PointCluster, IncrementalAndMergedMatchDirectStatistics) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0.0, 2.0);
  std::vector<Vec3> points;
  for (int i = 0; i < 50; ++i) points.emplace_back(100.0 + g(rng), -40.0 + g(rng), g(rng));

  PointCluster all, first, second;
  for (std::size_t i = 0; i < points.size(); ++i) {
    all.add(points[i]);
    (i < 20 ? first : second).add(points[i]);
  }
  first.merge(second);

  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= 50.0;
  Mat3 scatter = Mat3::Zero();
  for (const Vec3& p : points) scatter += (p - mean) * (p - mean).transpose();

  for (const PointCluster* c : {&all, &first}) {
    EXPECT_EQ(c->count, 50.0);
    EXPECT_LT((c->mean - mean).norm(), 1e-12);
    EXPECT_LT((c->scatter - scatter).norm(), 1e-9 * scatter.norm());
    EXPECT_LT((c->covariance() - scatter / 50.0).norm(), 1e-9 * scatter.norm());
  }
}

TEST(PointCluster, MergingWithEmptyIsIdentity) {
  PointCluster c, empty;
  c.add(Vec3(1, 2, 3));
  c.add(Vec3(2, 2, 3));
  PointCluster copy = c;
  copy.merge(empty);
  EXPECT_EQ(copy.count, 2.0);
  EXPECT_EQ(copy.mean, c.mean);
  empty.merge(c);
  EXPECT_EQ(empty.scatter, c.scatter);
  EXPECT_EQ(PointCluster().covariance(), Mat3::Zero());
}

}  // namespace
}  // namespace hba::ba

namespace hba::ba {
namespace {

TEST(FrameCluster, KeepsTheClusterIn80Bytes) {
  PointCluster points;
  for (const Vec3& p : {Vec3(1.0, 2.0, 3.5), Vec3(-0.5, 4.0, 1.25), Vec3(2.0, -1.0, 0.0)}) points.add(p);
  points.scatter = 0.5 * (points.scatter + points.scatter.transpose()).eval();  // as planes make them
  const FrameCluster kept(7, points);
  EXPECT_EQ(kept.frame, 7u);
  EXPECT_EQ(kept.count(), 3.0);
  EXPECT_EQ(kept.mean(), points.mean);
  EXPECT_EQ(kept.scatter(), points.scatter);  // bit for bit
  EXPECT_EQ(sizeof(FrameCluster), 80u);       // frame and count share 8 bytes
}

}  // namespace
}  // namespace hba::ba
