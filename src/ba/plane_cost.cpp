#include "hba/ba/plane_cost.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "core/symmetric_eigenvalues.hpp"
#include "hba/core/lie.hpp"

// Derivation (docs/ba.md has the long form). A frame-i point q = r + t_i
// with r = R_i p moves as dq = dt + dphi x r (+ 1/2 dphi x (dphi x r)).
// With A the world scatter, u1 <= u2 <= u3 its eigenvectors and lambda_k
// its eigenvalues:
//   d lambda1        = u1^T A_a u1
//   d2 lambda1 / ab  = u1^T A_ab u1 + 2 sum_{k=2,3} (u_k^T A_a u1)(u_k^T A_b u1) / (l1 - l_k)
// Since the centred points sum to zero, moving the mean drops out of A_a,
// and every term reduces to per-frame cluster sums:
//   g_i = N_i (c_i - mu)            (c_i: frame i's world centroid)
//   P_i = sum r (q - mu)^T = Sw_i + N_i rbar_i (c_i - mu)^T,  y_i = P_i u1
//   A_a u1 for the 6 coordinates: [ (u1.g_i) I + g_i u1^T | P_i^T [u1]x - [y_i]x ]
//   u1^T A_ab u1 = 2 sum_k j_a j_b - (2/N) c_a c_b + second-order rotation term,
// with per-point j = (u1, r x u1) and c_i = sum over frame i of j.
namespace hba::ba {
namespace {

// Per-frame quantities of one plane at the current poses.
struct WorldCluster {
  double n = 0.0;
  Vec3 rbar;    // R_i * sensor mean: centroid relative to the frame origin
  Mat3 sw;      // R_i S_i R_i^T, the centred scatter in world axes
  Vec3 offset;  // world centroid minus plane centroid (c_i - mu)
};

struct WorldPlane {
  std::vector<WorldCluster, Eigen::aligned_allocator<WorldCluster>> frames;
  double n = 0.0;
  Mat3 scatter = Mat3::Zero();
};

// Fills `world` (its storage reused: one per thread, no allocation per plane).
void toWorld(const PlaneObservation& plane, const FrameTransforms& frames, WorldPlane& world) {
  world.frames.resize(plane.clusters.size());
  world.n = 0.0;
  world.scatter.setZero();
  // Centroids relative to the first one: no large absolute coordinates are
  // squared, so kilometre-scale translations lose no precision.
  Vec3 reference = Vec3::Zero();
  Vec3 weighted = Vec3::Zero();
  for (std::size_t a = 0; a < plane.clusters.size(); ++a) {
    const FrameCluster& fc = plane.clusters[a];
    const Mat3& R = frames.R[fc.frame];
    WorldCluster& wc = world.frames[a];
    wc.n = fc.count();
    wc.rbar = R * fc.mean();
    wc.sw = R * fc.scatter() * R.transpose();
    const Vec3 centroid = wc.rbar + frames.t[fc.frame];
    if (a == 0) reference = centroid;
    wc.offset = centroid - reference;
    weighted += wc.n * wc.offset;
    world.n += wc.n;
  }
  const Vec3 mean_offset = world.n > 0.0 ? Vec3(weighted / world.n) : Vec3::Zero();
  for (WorldCluster& wc : world.frames) {
    wc.offset -= mean_offset;
    world.scatter += wc.sw + wc.n * wc.offset * wc.offset.transpose();
  }
  world.scatter = 0.5 * (world.scatter + world.scatter.transpose()).eval();
}

WorldPlane& threadWorldPlane() {
  thread_local WorldPlane world;
  return world;
}

// 1 / (l1 - lk) in the Hessian blows up when eigenvalues meet (a line or a
// blob, which the plane test rejects); drop the term there instead of
// producing an infinite Hessian.
double eigenGapWeight(double l1, double lk, double l3) {
  const double gap = lk - l1;
  if (!(gap > 1e-12 * std::max(l3, 1e-300))) return 0.0;
  return -2.0 / gap;
}

}  // namespace

double PlaneObservation::pointCount() const {
  double n = 0.0;
  for (const FrameCluster& fc : clusters) n += fc.count();
  return n;
}

FrameTransforms::FrameTransforms(const std::vector<Pose>& poses) {
  R.reserve(poses.size());
  t.reserve(poses.size());
  for (const Pose& pose : poses) {
    R.push_back(pose.R());
    t.push_back(pose.t);
  }
}

// The cost needs the world scatter only: one pass, no per-frame terms kept.
// The centroids' spread is summed about the first one and moved to their
// mean at the end (a plane is metres wide: nothing is lost to cancellation
// against its thinnest direction's share).
Mat3 planeScatter(const PlaneObservation& plane, const FrameTransforms& frames) {
  Mat3 scatter = Mat3::Zero();
  Vec3 reference = Vec3::Zero();
  Vec3 weighted = Vec3::Zero();
  double n = 0.0;
  for (std::size_t a = 0; a < plane.clusters.size(); ++a) {
    const FrameCluster& fc = plane.clusters[a];
    const Mat3& R = frames.R[fc.frame];
    const Vec3 centroid = R * fc.mean() + frames.t[fc.frame];
    if (a == 0) reference = centroid;
    const Vec3 offset = centroid - reference;
    const double count = fc.count();
    scatter += R * fc.scatter() * R.transpose() + count * offset * offset.transpose();
    weighted += count * offset;
    n += count;
  }
  if (n > 0.0) scatter -= weighted * weighted.transpose() / n;
  return 0.5 * (scatter + scatter.transpose());
}

double planeCost(const PlaneObservation& plane, const FrameTransforms& frames) {
  const Mat3 scatter = planeScatter(plane, frames);
  const double l1 = symmetricEigenvalues(scatter)(0);
  return std::max(l1, 0.0);  // rounding can make a perfect plane slightly negative
}

void planeTerms(const PlaneObservation& plane, const FrameTransforms& frames, PlaneTerms& terms) {
  WorldPlane& world = threadWorldPlane();
  toWorld(plane, frames, world);
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(world.scatter);
  const Vec3 lambda = eig.eigenvalues();
  const Vec3 u = eig.eigenvectors().col(0);
  const Vec3 u2 = eig.eigenvectors().col(1);
  const Vec3 u3 = eig.eigenvectors().col(2);
  const Mat3 hat_u = hat(u);
  const std::size_t F = world.frames.size();

  terms.cost = std::max(lambda(0), 0.0);
  terms.gradient.resize(F);
  terms.z.resize(F);
  terms.diagonal.resize(F);
  terms.weights << (world.n > 0.0 ? -2.0 / world.n : 0.0), eigenGapWeight(lambda(0), lambda(1), lambda(2)),
      eigenGapWeight(lambda(0), lambda(2), lambda(2));

  for (std::size_t a = 0; a < F; ++a) {
    const WorldCluster& wc = world.frames[a];
    const Vec3 g = wc.n * wc.offset;
    const Mat3 P = wc.sw + wc.n * wc.rbar * wc.offset.transpose();
    const Vec3 y = P * u;
    const double ug = u.dot(g);

    terms.gradient[a].head<3>() = 2.0 * ug * u;
    terms.gradient[a].tail<3>() = 2.0 * y.cross(u);

    // Columns: A_a u1 for the 6 coordinates of this frame.
    Eigen::Matrix<double, 3, 6> W;
    W.leftCols<3>() = ug * Mat3::Identity() + g * u.transpose();
    W.rightCols<3>() = P.transpose() * hat_u - hat(y);

    const Vec3 rbar_x_u = wc.rbar.cross(u);
    Eigen::Matrix<double, 3, 6>& Z = terms.z[a];
    Z.block<1, 3>(0, 0) = wc.n * u.transpose();
    Z.block<1, 3>(0, 3) = wc.n * rbar_x_u.transpose();
    Z.row(1) = u2.transpose() * W;
    Z.row(2) = u3.transpose() * W;

    // 2 * sum over the frame's points of j j^T, j = (u, r x u) ...
    const Mat3 second_moment = wc.sw + wc.n * wc.rbar * wc.rbar.transpose();
    Mat6& D = terms.diagonal[a];
    D.topLeftCorner<3, 3>() = 2.0 * wc.n * u * u.transpose();
    D.topRightCorner<3, 3>() = 2.0 * wc.n * u * rbar_x_u.transpose();
    D.bottomLeftCorner<3, 3>() = D.topRightCorner<3, 3>().transpose();
    D.bottomRightCorner<3, 3>() = 2.0 * hat_u.transpose() * second_moment * hat_u;
    // ... plus the second-order term of Exp(dphi) in the rotation block.
    D.bottomRightCorner<3, 3>() += y * u.transpose() + u * y.transpose() - 2.0 * u.dot(y) * Mat3::Identity();
  }
}

PlaneLinearization linearizePlane(const PlaneObservation& plane, const FrameTransforms& frames) {
  thread_local PlaneTerms terms;
  planeTerms(plane, frames, terms);
  const std::size_t F = terms.z.size();
  PlaneLinearization lin;
  lin.cost = terms.cost;
  lin.weights = terms.weights;
  lin.gradient.resize(6 * static_cast<Eigen::Index>(F));
  lin.Z.resize(3, 6 * static_cast<Eigen::Index>(F));
  for (std::size_t a = 0; a < F; ++a) {
    lin.gradient.segment<6>(6 * static_cast<Eigen::Index>(a)) = terms.gradient[a];
    lin.Z.middleCols<6>(6 * static_cast<Eigen::Index>(a)) = terms.z[a];
  }
  lin.diagonal.assign(terms.diagonal.begin(), terms.diagonal.end());
  return lin;
}

Eigen::MatrixXd PlaneLinearization::denseHessian() const {
  Eigen::MatrixXd H = Z.transpose() * weights.asDiagonal() * Z;
  for (std::size_t a = 0; a < diagonal.size(); ++a) H.block<6, 6>(6 * a, 6 * a) += diagonal[a];
  return H;
}

}  // namespace hba::ba
