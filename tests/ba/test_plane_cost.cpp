#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <tbb/global_control.h>

#include "hba/ba/plane_cost.hpp"
#include "hba/ba/plane_problem.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "pointwise_plane_cost.hpp"
#include "random_planes.hpp"

namespace hba::ba {
namespace {

using test::randomPlane;
using test::randomPoses;

// The convention of window_ba.hpp, written out independently of the solver:
// R <- Exp(dphi) R, t <- t + dt, delta = (dt, dphi) per frame.
std::vector<Pose> perturbed(const std::vector<Pose>& poses, const Eigen::VectorXd& delta) {
  std::vector<Pose> out;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    out.emplace_back(Mat3(so3Exp(delta.segment<3>(6 * i + 3)) * poses[i].R()),
                     Vec3(poses[i].t + delta.segment<3>(6 * i)));
  }
  return out;
}

Eigen::VectorXd unitStep(Eigen::Index size, Eigen::Index at, double h) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(size);
  d(at) = h;
  return d;
}

template <typename Cost>
Eigen::VectorXd numericGradient(const Cost& cost, const std::vector<Pose>& poses, double h) {
  const Eigen::Index n = 6 * static_cast<Eigen::Index>(poses.size());
  Eigen::VectorXd g(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    g(a) =
        (cost(perturbed(poses, unitStep(n, a, h))) - cost(perturbed(poses, unitStep(n, a, -h)))) / (2.0 * h);
  }
  return g;
}

// Central second differences of the cost itself: the Hessian of
// f(x (+) delta) at delta = 0 in exactly the perturbation convention.
template <typename Cost>
Eigen::MatrixXd numericHessian(const Cost& cost, const std::vector<Pose>& poses, double h) {
  const Eigen::Index n = 6 * static_cast<Eigen::Index>(poses.size());
  Eigen::MatrixXd H(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = a; b < n; ++b) {
      const Eigen::VectorXd da = unitStep(n, a, h);
      const Eigen::VectorXd db = unitStep(n, b, h);
      H(a, b) = (cost(perturbed(poses, da + db)) - cost(perturbed(poses, da - db)) -
                 cost(perturbed(poses, db - da)) + cost(perturbed(poses, -da - db))) /
                (4.0 * h * h);
      H(b, a) = H(a, b);
    }
  }
  return H;
}

double relativeError(const Eigen::MatrixXd& value, const Eigen::MatrixXd& reference) {
  return (value - reference).norm() / reference.norm();
}

TEST(PlaneCost, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<Pose> poses = randomPoses(rng, 3, 5.0);
    const auto plane = randomPlane(rng, poses, {0, 1, 2}, 20 + 10 * trial, 0.05);
    const auto cost = [&](const std::vector<Pose>& p) {
      return planeCost(plane.observation, FrameTransforms(p));
    };
    const PlaneLinearization lin = linearizePlane(plane.observation, FrameTransforms(poses));
    EXPECT_NEAR(lin.cost, cost(poses), 1e-12 * lin.cost);
    EXPECT_LT(relativeError(lin.gradient, numericGradient(cost, poses, 1e-6)), 1e-5);
    EXPECT_LT(relativeError(lin.denseHessian(), numericHessian(cost, poses, 1e-4)), 1e-5);
  }
}

TEST(PlaneCost, DerivativesHoldFarFromTheOrigin) {
  // Kilometre-scale translations (a top-layer window). Moving every frame by
  // one translation changes neither the cost nor its derivatives in this
  // convention, so the far evaluation must reproduce the near one: the
  // centred clusters keep full precision where finite differences cannot.
  std::mt19937 rng(5);
  const std::vector<Pose> near = randomPoses(rng, 3, 3.0);
  const auto plane = randomPlane(rng, near, {0, 1, 2}, 30, 0.05);
  std::vector<Pose> far = near;
  for (Pose& p : far) p.t += Vec3(2500.0, -1800.0, 40.0);
  const PlaneLinearization at_near = linearizePlane(plane.observation, FrameTransforms(near));
  const PlaneLinearization at_far = linearizePlane(plane.observation, FrameTransforms(far));
  EXPECT_NEAR(at_far.cost, at_near.cost, 1e-9 * at_near.cost);
  EXPECT_LT(relativeError(at_far.gradient, at_near.gradient), 1e-7);
  EXPECT_LT(relativeError(at_far.denseHessian(), at_near.denseHessian()), 1e-7);
}

TEST(PlaneProblem, AssembledDerivativesMatchFiniteDifferences) {
  // Planes seen by different frame subsets: checks the cross-frame blocks
  // and the scatter of local blocks into the window's rows.
  std::mt19937 rng(9);
  const std::vector<Pose> poses = randomPoses(rng, 4, 4.0);
  std::vector<PlaneObservation> planes;
  planes.push_back(randomPlane(rng, poses, {0, 2, 3}, 25, 0.04).observation);
  planes.push_back(randomPlane(rng, poses, {1, 2}, 25, 0.04).observation);
  planes.push_back(randomPlane(rng, poses, {0, 1, 3}, 25, 0.04).observation);
  const PlaneProblem problem(planes, 4);
  const auto cost = [&](const std::vector<Pose>& p) { return problem.cost(p); };

  const Linearization lin = problem.linearize(poses);
  EXPECT_NEAR(lin.cost, problem.cost(poses), 1e-12 * lin.cost);
  EXPECT_LT(relativeError(lin.gradient, numericGradient(cost, poses, 1e-6)), 1e-5);
  EXPECT_LT(relativeError(lin.hessian, numericHessian(cost, poses, 1e-4)), 1e-5);
  EXPECT_LT((lin.hessian - lin.hessian.transpose()).norm(), 1e-12 * lin.hessian.norm());
}

// Many planes: linearize() sums them in chunks, each into its own Hessian.
// The result must be the plain sum of every plane's own dense Hessian, and
// bit for bit the same on one thread as on two.
TEST(PlaneProblem, ChunkedAssemblyIsThePlanesSumForAnyThreadCount) {
  std::mt19937 rng(17);
  const int frames = 8;
  const std::vector<Pose> poses = randomPoses(rng, frames, 4.0);
  std::vector<PlaneObservation> planes;
  for (int p = 0; p < 400; ++p) {
    std::vector<std::uint32_t> seen;
    for (std::uint32_t f = 0; f < static_cast<std::uint32_t>(frames); ++f) {
      if ((p + f) % 3 != 0) seen.push_back(f);
    }
    planes.push_back(randomPlane(rng, poses, seen, 8, 0.02).observation);
  }
  const PlaneProblem problem(planes, frames);

  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6 * frames, 6 * frames);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(6 * frames);
  for (const PlaneObservation& plane : planes) {
    const PlaneLinearization lin = linearizePlane(plane, FrameTransforms(poses));
    const Eigen::MatrixXd local = lin.denseHessian();
    for (std::size_t a = 0; a < plane.clusters.size(); ++a) {
      const auto i = static_cast<Eigen::Index>(6 * plane.clusters[a].frame);
      g.segment<6>(i) += lin.gradient.segment<6>(6 * static_cast<Eigen::Index>(a));
      for (std::size_t b = 0; b < plane.clusters.size(); ++b) {
        const auto j = static_cast<Eigen::Index>(6 * plane.clusters[b].frame);
        H.block<6, 6>(i, j) +=
            local.block<6, 6>(6 * static_cast<Eigen::Index>(a), 6 * static_cast<Eigen::Index>(b));
      }
    }
  }
  auto linearizeWith = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return problem.linearize(poses);
  };
  const Linearization one = linearizeWith(1);
  const Linearization two = linearizeWith(2);
  EXPECT_LT(relativeError(one.hessian, H), 1e-12);
  EXPECT_LT(relativeError(one.gradient, g), 1e-12);
  EXPECT_EQ(one.hessian, two.hessian);
  EXPECT_EQ(one.gradient, two.gradient);
  EXPECT_EQ(one.cost, two.cost);
}

// linearize() builds half the Hessian from the frame order, so a plane whose
// clusters are out of order (or repeat a frame) must be refused, not summed wrong.
TEST(PlaneProblem, RefusesClustersOutOfFrameOrder) {
  std::mt19937 rng(5);
  const std::vector<Pose> poses = randomPoses(rng, 3, 4.0);
  PlaneObservation plane = randomPlane(rng, poses, {0, 2}, 25, 0.04).observation;
  EXPECT_NO_THROW(PlaneProblem({plane}, 3));
  std::swap(plane.clusters[0], plane.clusters[1]);
  EXPECT_THROW(PlaneProblem({plane}, 3), Error);
  plane.clusters[0].frame = plane.clusters[1].frame;
  EXPECT_THROW(PlaneProblem({plane}, 3), Error);
}

TEST(PlaneProblem, CostIsInvariantToARigidMotionOfAllFrames) {
  std::mt19937 rng(21);
  const std::vector<Pose> poses = randomPoses(rng, 3, 4.0);
  const PlaneProblem problem({randomPlane(rng, poses, {0, 1, 2}, 30, 0.05).observation}, 3);
  const Pose motion(so3Exp(Vec3(0.3, -0.2, 0.5)), Vec3(4.0, -2.0, 1.0));
  std::vector<Pose> moved;
  for (const Pose& p : poses) moved.push_back(motion * p);
  EXPECT_NEAR(problem.cost(moved), problem.cost(poses), 1e-9 * problem.cost(poses));
}

// Brute force, independent of any eigen solver: the mean squared distance
// of the raw world points to the best plane, minimised over plane normals by
// a grid search on the sphere refined by shrinking coordinate steps.
double bruteForceSumSquaredDistance(const std::vector<Vec3>& points) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& q : points) centroid += q;
  centroid /= static_cast<double>(points.size());
  const auto sumSq = [&](double theta, double phi) {
    const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    double s = 0.0;
    for (const Vec3& q : points) s += std::pow(n.dot(q - centroid), 2);
    return s;
  };
  double best_theta = 0.0, best_phi = 0.0, best = sumSq(0.0, 0.0);
  for (int i = 0; i <= 60; ++i) {
    for (int j = 0; j < 120; ++j) {
      const double th = M_PI * i / 60.0, ph = 2.0 * M_PI * j / 120.0;
      if (sumSq(th, ph) < best) best = sumSq(th, ph), best_theta = th, best_phi = ph;
    }
  }
  for (double step = 0.05; step > 1e-12; step *= 0.5) {
    for (bool improved = true; improved;) {
      improved = false;
      for (const auto& [dth, dph] : {std::pair{step, 0.0}, {-step, 0.0}, {0.0, step}, {0.0, -step}}) {
        const double s = sumSq(best_theta + dth, best_phi + dph);
        if (s < best) best = s, best_theta += dth, best_phi += dph, improved = true;
      }
    }
  }
  return best;
}

TEST(PlaneCost, EqualsSumOfSquaredDistancesToBestPlane) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 4; ++trial) {
    const std::vector<Pose> poses = randomPoses(rng, 3, 6.0);
    const auto plane = randomPlane(rng, poses, {0, 1, 2}, 40, 0.03 + 0.02 * trial);
    std::vector<Vec3> world;
    for (std::size_t a = 0; a < plane.sensor_points.size(); ++a) {
      for (const Vec3& p : plane.sensor_points[a]) world.push_back(poses[a] * p);
    }
    const double cost = planeCost(plane.observation, FrameTransforms(poses));
    const double brute = bruteForceSumSquaredDistance(world);
    EXPECT_NEAR(cost, brute, 1e-8 * brute);
    // Hence cost / N is the mean squared point-to-plane distance.
    EXPECT_NEAR(cost / plane.observation.pointCount(), brute / world.size(), 1e-8 * brute);
  }
}

// The cost sums the frames' centroids about the first one in one pass: a
// thin plane seen by many frames far from the origin keeps its thickness.
TEST(PlaneCost, OnePassKeepsAThinPlaneFarFromTheOrigin) {
  std::mt19937 rng(17);
  std::vector<Pose> poses = randomPoses(rng, 20, 6.0);
  std::vector<std::uint32_t> frames(poses.size());
  for (std::uint32_t f = 0; f < frames.size(); ++f) frames[f] = f;
  const auto plane = randomPlane(rng, poses, frames, 30, 0.001);
  for (Pose& pose : poses) pose.t += Vec3(2500.0, -1800.0, 40.0);
  std::vector<Vec3> world;
  for (std::size_t a = 0; a < plane.sensor_points.size(); ++a) {
    for (const Vec3& p : plane.sensor_points[a]) world.push_back(poses[a] * p);
  }
  const double brute = bruteForceSumSquaredDistance(world);
  EXPECT_NEAR(planeCost(plane.observation, FrameTransforms(poses)), brute, 1e-6 * brute);
  // The same as the linearization's, which takes the offsets about their mean.
  const PlaneLinearization lin = linearizePlane(plane.observation, FrameTransforms(poses));
  EXPECT_NEAR(planeCost(plane.observation, FrameTransforms(poses)), lin.cost, 1e-9 * lin.cost);
}

TEST(PlaneCost, ClusterFormEqualsPointwiseEvaluation) {
  std::mt19937 rng(31);
  const std::vector<Pose> poses = randomPoses(rng, 4, 5.0);
  const auto plane = randomPlane(rng, poses, {0, 1, 2, 3}, 50, 0.03);
  const PlaneLinearization lin = linearizePlane(plane.observation, FrameTransforms(poses));
  const test::PointwiseResult naive = test::pointwisePlaneDerivatives(plane.sensor_points, poses);
  EXPECT_NEAR(lin.cost, naive.cost, 1e-9 * naive.cost);
  EXPECT_LT(relativeError(lin.gradient, naive.gradient), 1e-9);
  EXPECT_LT(relativeError(lin.denseHessian(), naive.hessian), 1e-9);
}

TEST(PlaneCost, DegeneratePlanesGiveFiniteResults) {
  // All points identical: A = 0, every eigenvalue equal.
  PlaneObservation blob;
  for (std::uint32_t f = 0; f < 2; ++f) {
    PointCluster points;
    for (int k = 0; k < 5; ++k) points.add(Vec3(1, 2, 3));
    blob.clusters.emplace_back(f, points);
  }
  const std::vector<Pose> poses(2, Pose::identity());
  const PlaneLinearization lin = linearizePlane(blob, FrameTransforms(poses));
  EXPECT_EQ(lin.cost, 0.0);
  EXPECT_TRUE(lin.gradient.allFinite());
  EXPECT_TRUE(lin.denseHessian().allFinite());
}

}  // namespace
}  // namespace hba::ba
