#pragma once
// Sufficient statistics of a set of points: count, mean and centred scatter
// sum (p - mean)(p - mean)^T. Centring keeps the numbers small (no
// cancellation in M/N - mu mu^T far from the origin).
#include <cstddef>

#include "hba/core/types.hpp"

namespace hba {

struct PointCluster {
  double count = 0.0;
  Vec3 mean = Vec3::Zero();
  Mat3 scatter = Mat3::Zero();

  void add(const Vec3& p);                // one point (Welford update)
  void merge(const PointCluster& other);  // parallel-axis combination
  // Covariance scatter / count (zero for an empty cluster).
  Mat3 covariance() const;
};

}  // namespace hba
