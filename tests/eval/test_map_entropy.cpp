// Mean map entropy: hand-computed cases, a brute-force cross-check, and the
// property that makes it useful (a doubled surface scores worse).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hba/core/error.hpp"
#include "hba/eval/map_entropy.hpp"

namespace hba::eval {
namespace {

PointCloud cubeCorners(float edge) {
  PointCloud c;
  for (int i = 0; i < 8; ++i) c.add(Vec3f(edge * (i & 1), edge * ((i >> 1) & 1), edge * ((i >> 2) & 1)));
  return c;
}

TEST(MapEntropy, CubeCornersByHand) {
  // Every corner sees all 8 corners; each axis is +-0.05 about the centre:
  // population variance 0.0025 per axis, no correlation.
  const PointCloud cube = cubeCorners(0.1f);
  MmeSettings s;
  s.min_neighbors = 7;
  s.sample_covariance = false;
  const double expected = 0.5 * (3.0 * std::log(2.0 * M_PI * M_E) + 3.0 * std::log(0.0025));
  MmeResult r = meanMapEntropy(cube, s);
  EXPECT_EQ(r.points, 8u);
  EXPECT_EQ(r.used, 8u);
  EXPECT_NEAR(r.mme, expected, 1e-5);  // float coordinates

  s.sample_covariance = true;  // divisor 7 instead of 8
  EXPECT_NEAR(meanMapEntropy(cube, s).mme, expected + 1.5 * std::log(8.0 / 7.0), 1e-5);
}

TEST(MapEntropy, NeighbourCountRules) {
  const PointCloud cube = cubeCorners(0.1f);
  MmeSettings s;
  s.min_neighbors = 8;
  s.strictly_more = true;  // 8 > 8 fails
  EXPECT_EQ(meanMapEntropy(cube, s).used, 0u);
  EXPECT_TRUE(std::isnan(meanMapEntropy(cube, s).mme));
  s.strictly_more = false;  // 8 >= 8 passes
  EXPECT_EQ(meanMapEntropy(cube, s).used, 8u);
  s.count_query = false;  // now only 7 neighbours each
  EXPECT_EQ(meanMapEntropy(cube, s).used, 0u);
}

TEST(MapEntropy, DegenerateNeighbourhoodsAreSkipped) {
  PointCloud line;  // collinear points: det = 0, no finite entropy
  for (int i = 0; i < 30; ++i) line.add(Vec3f(0.01f * i, 0, 0));
  EXPECT_EQ(meanMapEntropy(line).used, 0u);
  EXPECT_THROW(meanMapEntropy(line, MmeSettings{0.0}), Error);
}

PointCloud noisyPlane(std::mt19937& rng, float z, int n) {
  std::uniform_real_distribution<float> xy(0.0f, 2.0f);
  std::normal_distribution<float> noise(0.0f, 0.005f);
  PointCloud c;
  for (int i = 0; i < n; ++i) c.add(Vec3f(xy(rng), xy(rng), z + noise(rng)));
  return c;
}

// O(n^2) reference written the obvious way.
double bruteForceMme(const PointCloud& c, const MmeSettings& s) {
  double sum = 0.0;
  int used = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    std::vector<Vec3> near;
    for (std::size_t j = 0; j < c.size(); ++j) {
      if (j == i && !s.count_query) continue;
      if ((c.points[j] - c.points[i]).squaredNorm() < s.radius * s.radius)
        near.push_back(c.points[j].cast<double>());
    }
    const auto n = static_cast<int>(near.size());
    if (s.strictly_more ? n <= s.min_neighbors : n < s.min_neighbors) continue;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : near) mean += p;
    mean /= n;
    Mat3 cov = Mat3::Zero();
    for (const Vec3& p : near) cov += (p - mean) * (p - mean).transpose();
    cov /= s.sample_covariance ? n - 1 : n;
    const double det = (2.0 * M_PI * M_E * cov).determinant();
    if (det <= 0) continue;
    sum += 0.5 * std::log(det);
    ++used;
  }
  return sum / used;
}

TEST(MapEntropy, MatchesBruteForceForEveryRule) {
  std::mt19937 rng(7);
  PointCloud cloud = noisyPlane(rng, 0.0f, 1500);
  for (const Vec3f& p : noisyPlane(rng, 0.3f, 500).points) cloud.add(p);
  for (int rule = 0; rule < 8; ++rule) {
    MmeSettings s;
    s.radius = 0.2;
    s.strictly_more = rule & 1;
    s.count_query = rule & 2;
    s.sample_covariance = rule & 4;
    EXPECT_NEAR(meanMapEntropy(cloud, s).mme, bruteForceMme(cloud, s), 1e-9) << "rule " << rule;
  }
}

TEST(MapEntropy, DoubleWallScoresWorseThanASingleOne) {
  std::mt19937 rng(3);
  const PointCloud single = noisyPlane(rng, 0.0f, 4000);
  PointCloud doubled = noisyPlane(rng, 0.0f, 2000);
  for (const Vec3f& p : noisyPlane(rng, 0.08f, 2000).points) doubled.add(p);
  EXPECT_GT(meanMapEntropy(doubled).mme, meanMapEntropy(single).mme + 1.0);
}

}  // namespace
}  // namespace hba::eval
