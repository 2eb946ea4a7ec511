#include "hba/core/point_cluster.hpp"

namespace hba {

void PointCluster::add(const Vec3& p) {
  count += 1.0;
  const Vec3 before = p - mean;
  mean += before / count;
  // Welford: (p - old mean)(p - new mean)^T; symmetric up to rounding, and
  // builders that need exact symmetry use the two-pass form instead.
  scatter.noalias() += before * (p - mean).transpose();
}

void PointCluster::merge(const PointCluster& other) {
  if (other.count <= 0.0) return;
  if (count <= 0.0) {
    *this = other;
    return;
  }
  const double total = count + other.count;
  const Vec3 delta = other.mean - mean;
  scatter += other.scatter + (count * other.count / total) * delta * delta.transpose();
  mean += (other.count / total) * delta;
  count = total;
}

Mat3 PointCluster::covariance() const { return count > 0.0 ? Mat3(scatter / count) : Mat3::Zero(); }

}  // namespace hba
