#include "pointwise_plane_cost.hpp"

#include <Eigen/Eigenvalues>

#include "hba/core/lie.hpp"

namespace hba::test {

PointwiseResult pointwisePlaneDerivatives(const std::vector<std::vector<Vec3>>& points,
                                          const std::vector<Pose>& poses) {
  const std::size_t F = points.size();
  std::vector<std::vector<Vec3>> rotated(F), world(F);
  Vec3 mu = Vec3::Zero();
  double n = 0.0;
  for (std::size_t a = 0; a < F; ++a) {
    const Mat3 R = poses[a].R();
    for (const Vec3& p : points[a]) {
      rotated[a].push_back(R * p);
      world[a].push_back(rotated[a].back() + poses[a].t);
      mu += world[a].back();
      n += 1.0;
    }
  }
  mu /= n;
  Mat3 A = Mat3::Zero();
  for (const auto& frame : world) {
    for (const Vec3& q : frame) A += (q - mu) * (q - mu).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(A);
  const Vec3 lambda = eig.eigenvalues();
  const Vec3 u = eig.eigenvectors().col(0);

  PointwiseResult out;
  out.cost = lambda(0);
  out.gradient.setZero(6 * F);
  out.hessian.setZero(6 * F, 6 * F);
  std::vector<Vec6> jsum(F, Vec6::Zero());
  std::vector<Eigen::Matrix<double, 3, 6>> W(F);
  for (std::size_t a = 0; a < F; ++a) {
    W[a].setZero();
    Mat6 D = Mat6::Zero();
    for (std::size_t k = 0; k < world[a].size(); ++k) {
      const Vec3& r = rotated[a][k];
      const Vec3 e = world[a][k] - mu;
      const double d = u.dot(e);  // signed distance to the plane
      Vec6 j;
      j << u, r.cross(u);  // d(u . q) / d(dt, dphi)
      out.gradient.segment<6>(6 * a) += 2.0 * d * j;
      jsum[a] += j;
      D += 2.0 * j * j.transpose();
      D.bottomRightCorner<3, 3>() +=
          d * (r * u.transpose() + u * r.transpose()) - 2.0 * d * u.dot(r) * Mat3::Identity();
      W[a].leftCols<3>() += d * Mat3::Identity() + e * u.transpose();
      W[a].rightCols<3>() += -d * hat(r) + e * r.cross(u).transpose();
    }
    out.hessian.block<6, 6>(6 * a, 6 * a) += D;
  }
  for (std::size_t a = 0; a < F; ++a) {
    for (std::size_t b = 0; b < F; ++b) {
      Mat6 block = -(2.0 / n) * jsum[a] * jsum[b].transpose();
      for (int k = 1; k < 3; ++k) {
        const Vec3 uk = eig.eigenvectors().col(k);
        block += 2.0 / (lambda(0) - lambda(k)) * (W[a].transpose() * uk) * (uk.transpose() * W[b]);
      }
      out.hessian.block<6, 6>(6 * a, 6 * b) += block;
    }
  }
  return out;
}

}  // namespace hba::test
