#include "hba/closure/point_features.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <array>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <Eigen/Eigenvalues>

#include "core/kd_tree.hpp"
#include "hba/voxel/downsample.hpp"

namespace hba::closure {
namespace {

constexpr int kBins = 11;

// The smallest-variance direction of the neighbours (of either sign); zero
// when too few neighbours.
Vec3f fitNormal(const std::vector<Vec3f>& points, std::size_t i, const KdTree<3>& tree, float radius,
                std::size_t min_neighbours) {
  const auto found = tree.within(points[i], radius);
  if (found.size() < min_neighbours) return Vec3f::Zero();
  Vec3 mean = Vec3::Zero();
  for (const auto& [j, d] : found) mean += points[j].cast<double>();
  mean /= static_cast<double>(found.size());
  Mat3 scatter = Mat3::Zero();
  for (const auto& [j, d] : found) {
    const Vec3 e = points[j].cast<double>() - mean;
    scatter += e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(scatter);
  return solver.eigenvectors().col(0).cast<float>();
}

constexpr float kPi = 3.14159265F;

int bin(float value, float low, float high) {
  const int b = static_cast<int>(std::floor(kBins * (value - low) / (high - low)));
  return std::clamp(b, 0, kBins - 1);
}

// Rusu's three angles of the Darboux frame between two points, as bins of
// a simple histogram (-1: no frame). The normals' signs are not used: a map
// has no sensor position to turn them towards, and one surface seen from
// two sides must describe alike. So the frame sits on the point whose normal
// is closer to the line, that normal turned to point along the line, the
// other turned to agree with it; either point gives the same bins. In
// float: bins of 1/11 of the range need no more.
std::array<int, 3> pairBins(const Vec3f& p, const Vec3f& np, const Vec3f& q, const Vec3f& nq) {
  Vec3f d = q - p;
  const float distance = d.norm();
  if (distance <= 0.0F) return {-1, -1, -1};
  d /= distance;
  Vec3f n1 = np, n2 = nq;
  if (std::abs(n1.dot(d)) < std::abs(n2.dot(d))) {
    std::swap(n1, n2);
    d = -d;
  }
  if (n1.dot(d) < 0.0F) n1 = -n1;
  if (n1.dot(n2) < 0.0F) n2 = -n2;
  Vec3f v = d.cross(n1);
  const float v_norm = v.norm();
  if (v_norm <= 1e-6F) return {-1, -1, -1};
  v /= v_norm;
  const Vec3f w = n1.cross(v);
  const float theta = std::atan2(w.dot(n2), n1.dot(n2));  // n1.n2 >= 0: within +-pi/2
  return {bin(theta, -kPi / 2, kPi / 2), kBins + bin(v.dot(n2), -1.0F, 1.0F),
          2 * kBins + bin(n1.dot(d), 0.0F, 1.0F)};
}

void normalise(Fpfh& histogram) {
  for (int part = 0; part < 3; ++part) {
    const float sum = histogram.segment<kBins>(part * kBins).sum();
    if (sum > 0.0F) histogram.segment<kBins>(part * kBins) *= 100.0F / sum;
  }
}

// The first point of each occupied cell of edge `cell`, in point order.
std::vector<std::uint32_t> keypointsOf(const std::vector<Vec3f>& points, double cell) {
  std::unordered_set<std::uint64_t> taken;
  std::vector<std::uint32_t> keypoints;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3i c = (points[i].cast<double>() / cell).array().floor().cast<int>();
    const std::uint64_t key = (static_cast<std::uint64_t>(c.x() & 0x1FFFFF) << 42) |
                              (static_cast<std::uint64_t>(c.y() & 0x1FFFFF) << 21) |
                              static_cast<std::uint64_t>(c.z() & 0x1FFFFF);
    if (taken.insert(key).second) keypoints.push_back(static_cast<std::uint32_t>(i));
  }
  return keypoints;
}

}  // namespace

FeatureCloud describeCloud(const PointCloud& cloud, double voxel, const FeatureSettings& settings) {
  const PointCloud sparse = voxel::downsample(cloud, voxel, 4);
  const KdTree<3> all(sparse.points);
  std::vector<Vec3f> normals(sparse.size());
  const auto normal_radius = static_cast<float>(settings.normal_radius * voxel);
  tbb::parallel_for(std::size_t{0}, sparse.size(), [&](std::size_t i) {
    normals[i] = fitNormal(sparse.points, i, all, normal_radius, settings.min_neighbours);
  });

  FeatureCloud out;
  out.voxel = voxel;
  for (std::size_t i = 0; i < sparse.size(); ++i) {
    if (normals[i].isZero()) continue;
    out.points.push_back(sparse.points[i]);
    out.normals.push_back(normals[i]);
  }
  const KdTree<3> kept(out.points);
  out.keypoints = keypointsOf(out.points, settings.keypoint_voxels * voxel);
  const auto feature_radius = static_cast<float>(settings.feature_radius * voxel);
  // Every point's simple histogram (a keypoint's neighbours need theirs),
  // then the keypoints' fast ones: their own plus their neighbours' weighted
  // by nearness.
  // Each pair once (its bins are the same from either end), counted into
  // both points' histograms: per-thread counts, summed exactly (integers).
  std::vector<std::vector<std::pair<std::uint32_t, float>>> neighbours(out.points.size());
  tbb::enumerable_thread_specific<std::vector<Fpfh>> counts(
      [&] { return std::vector<Fpfh>(out.points.size(), Fpfh::Zero()); });
  tbb::parallel_for(std::size_t{0}, out.points.size(), [&](std::size_t i) {
    neighbours[i] = kept.within(out.points[i], feature_radius);
    std::vector<Fpfh>& mine = counts.local();
    for (const auto& [j, d] : neighbours[i]) {
      if (j <= i) continue;
      const std::array<int, 3> bins = pairBins(out.points[i], out.normals[i], out.points[j], out.normals[j]);
      if (bins[0] < 0) continue;
      for (const int b : bins) {
        mine[i][b] += 1.0F;
        mine[j][b] += 1.0F;
      }
    }
  });
  std::vector<Fpfh> simple(out.points.size(), Fpfh::Zero());
  for (const std::vector<Fpfh>& part : counts) {
    for (std::size_t i = 0; i < simple.size(); ++i) simple[i] += part[i];
  }
  for (Fpfh& histogram : simple) normalise(histogram);
  out.features.assign(out.keypoints.size(), Fpfh::Zero());
  tbb::parallel_for(std::size_t{0}, out.keypoints.size(), [&](std::size_t k) {
    const std::uint32_t i = out.keypoints[k];
    Fpfh spread = Fpfh::Zero();
    for (const auto& [j, d_sq] : neighbours[i]) {
      if (j != i && d_sq > 0.0F) spread += simple[j] / std::sqrt(d_sq);
    }
    normalise(spread);
    out.features[k] = simple[i] + spread;
  });
  return out;
}

}  // namespace hba::closure
