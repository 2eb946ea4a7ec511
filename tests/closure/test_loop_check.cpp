// verifyLoop on a simulated drive that revisits its start, against the
// simulator's ground truth.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <tuple>

#include <tbb/global_control.h>

#include "hba/closure/loop_check.hpp"
#include "hba/core/lie.hpp"
#include "simulated_scans.hpp"

namespace hba::closure {
namespace {

using test::kLap;
using test::LazySimulatedScans;

// "A few mm, hundredths of a degree": the planes of two ten-scan maps hold
// their relative pose far tighter than the drift the loop corrects.
constexpr double kTranslationTolerance = 0.003;
constexpr double kRotationToleranceDeg = 0.02;

double translationError(const Pose& a, const Pose& b) { return (a.t - b.t).norm(); }
double rotationErrorDeg(const Pose& a, const Pose& b) {
  return so3Log(relative(a, b).q).norm() * 180.0 / M_PI;
}

// `pose` moved by (dx, dy) m and turned by `yaw_deg` in the frame it is expressed in.
Pose offsetBy(const Pose& pose, double dx, double dy, double yaw_deg) {
  const Pose offset(so3Exp(Vec3(0, 0, yaw_deg * M_PI / 180.0)), Vec3(dx, dy, 0.0));
  return offset * pose;
}

LoopCheckSettings withSearch() {
  LoopCheckSettings settings;
  settings.search_radius_m = 5.0;
  settings.search_yaw_deg = 10.0;
  return settings;
}

class LoopCheckOnDrive : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    simulation_ = new sim::Simulation(sim::prepareSimulation(test::revisitingDrive(sim::SensorModel::Vlp16)));
    scans_ = new LazySimulatedScans(*simulation_, 0.1);
  }
  static void TearDownTestSuite() {
    delete scans_;
    delete simulation_;
  }

  static Pose truthBetween(std::size_t from, std::size_t to) {
    return relative(simulation_->truth.poses[from], simulation_->truth.poses[to]);
  }
  // Checked against the drifting poses a pyramid's layer 1 would hold.
  static LoopCheck check(const LoopPair& pair, const LoopCheckSettings& settings = {}) {
    return verifyLoop(*scans_, simulation_->initial, pair, settings);
  }

  static sim::Simulation* simulation_;
  static LazySimulatedScans* scans_;
};

sim::Simulation* LoopCheckOnDrive::simulation_ = nullptr;
LazySimulatedScans* LoopCheckOnDrive::scans_ = nullptr;

TEST_F(LoopCheckOnDrive, ExactGuessIsAcceptedAtTheTruth) {
  for (const std::size_t from : {10, 20}) {
    const std::size_t to = from + kLap;
    const Pose truth = truthBetween(from, to);
    const LoopCheck result = check({from, to, truth});
    ASSERT_TRUE(result.accepted) << result.reason;
    EXPECT_EQ(result.reason, "");
    EXPECT_LT(translationError(result.relative, truth), kTranslationTolerance);
    EXPECT_LT(rotationErrorDeg(result.relative, truth), kRotationToleranceDeg);
    EXPECT_GE(result.overlap, LoopCheckSettings{}.min_overlap);
    EXPECT_LT(result.rms_m, 0.03);  // range noise 2 cm, averaged by the downsampling
  }
}

TEST_F(LoopCheckOnDrive, TheDriftedPosesAreTheGuessWhenNoneIsGiven) {
  const std::size_t from = 10;
  const std::size_t to = from + kLap;
  const Pose drifted = relative(simulation_->initial[from], simulation_->initial[to]);
  const Pose truth = truthBetween(from, to);
  ASSERT_GT(translationError(drifted, truth), 0.1);  // the loop is open
  const LoopCheck result = check({from, to, std::nullopt});
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_LT(translationError(result.relative, truth), kTranslationTolerance);
  EXPECT_LT(rotationErrorDeg(result.relative, truth), kRotationToleranceDeg);
  EXPECT_NEAR(result.correction_m, translationError(drifted, result.relative), 1e-9);
  EXPECT_NEAR(result.correction_deg, rotationErrorDeg(drifted, result.relative), 1e-9);
}

TEST_F(LoopCheckOnDrive, SearchFindsAGuessMetresAndDegreesOff) {
  const std::size_t from = 10;
  const std::size_t to = from + kLap;
  const Pose truth = truthBetween(from, to);
  for (const auto& [dx, dy, yaw] : {std::tuple{3.0, -2.0, 7.0}, {-2.5, 1.5, -6.0}, {0.0, 4.0, 9.0}}) {
    const Pose guess = offsetBy(truth, dx, dy, yaw);
    const LoopCheck searched = check({from, to, guess}, withSearch());
    ASSERT_TRUE(searched.accepted) << searched.reason;
    EXPECT_LT(translationError(searched.relative, truth), kTranslationTolerance);
    EXPECT_LT(rotationErrorDeg(searched.relative, truth), kRotationToleranceDeg);
    EXPECT_GT(searched.search_score, searched.search_second_score);
    EXPECT_GT(searched.correction_m, 2.0);

    // Without the search the plane BA cannot reach so far: it must not
    // return a wrong factor (an accepted pose is the right one).
    const LoopCheck trusted = check({from, to, guess});
    EXPECT_FALSE(trusted.accepted && translationError(trusted.relative, truth) > kTranslationTolerance)
        << "accepted " << translationError(trusted.relative, truth) << " m from the truth";
    if (!trusted.accepted) {
      EXPECT_NE(trusted.reason, "");
    }
  }
}

TEST_F(LoopCheckOnDrive, PairsAtDifferentPlacesAreRejected) {
  // A bad place recognizer's loops: frames 10 to 50 m apart along the
  // block, each claimed to coincide.
  const std::pair<std::size_t, std::size_t> wrong[] = {{10, 60}, {10, 110}, {60, 160}, {110, 210}, {20, 40}};
  for (const LoopCheckSettings& settings : {LoopCheckSettings{}, withSearch()}) {
    for (const auto& [from, to] : wrong) {
      const LoopCheck result = check({from, to, Pose()}, settings);
      EXPECT_FALSE(result.accepted) << from << "-" << to << " accepted";
      EXPECT_NE(result.reason, "") << from << "-" << to;
    }
  }
}

TEST_F(LoopCheckOnDrive, InformationIsPositiveDefiniteAndGrowsWithThePlanes) {
  const std::size_t from = 10;
  const std::size_t to = from + kLap;
  const Pose truth = truthBetween(from, to);
  LoopCheckSettings few;
  few.neighbourhood_frames = 2;
  LoopCheckSettings more;
  more.neighbourhood_frames = 8;
  const LoopCheck small = check({from, to, truth}, few);
  const LoopCheck large = check({from, to, truth}, more);
  ASSERT_TRUE(small.accepted) << small.reason;
  ASSERT_TRUE(large.accepted) << large.reason;
  for (const LoopCheck* result : {&small, &large}) {
    const Mat6& info = result->information;
    EXPECT_LT((info - info.transpose()).norm(), 1e-9 * info.norm());
    const Eigen::SelfAdjointEigenSolver<Mat6> eigen(info);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
    // Not a clamped floor: every direction is held by the planes themselves.
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 1e-4 * eigen.eigenvalues().maxCoeff());
  }
  EXPECT_GT(large.shared_planes, small.shared_planes);
  EXPECT_GT(large.information.trace(), small.information.trace());
  EXPECT_GT(std::log(large.information.determinant()), std::log(small.information.determinant()));
  EXPECT_LT(large.sigma_m, small.sigma_m);
}

TEST_F(LoopCheckOnDrive, SameResultTwiceAndOnAnyThreadCount) {
  const std::size_t from = 20;
  const LoopPair pair{from, from + kLap, offsetBy(truthBetween(from, from + kLap), 1.5, -1.0, 4.0)};
  std::vector<LoopCheck> results;
  for (const int threads : {1, 2, 1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    results.push_back(check(pair, withSearch()));
  }
  ASSERT_TRUE(results.front().accepted) << results.front().reason;
  for (const LoopCheck& r : results) {
    EXPECT_EQ(r.relative.t, results.front().relative.t);
    EXPECT_EQ(r.relative.q.coeffs(), results.front().relative.q.coeffs());
    EXPECT_EQ(r.information, results.front().information);
    EXPECT_EQ(r.shared_planes, results.front().shared_planes);
    EXPECT_EQ(r.overlap, results.front().overlap);
    EXPECT_EQ(r.search_score, results.front().search_score);
  }
}

// The same defaults hold for a forward-looking solid-state sensor (70 degree
// cone): fewer planes, but the search and the BA still find the truth.
TEST(LoopCheckLivox, RevisitIsFoundFromAGuessMetresOff) {
  const sim::Simulation simulation = sim::prepareSimulation(test::revisitingDrive(sim::SensorModel::Livox));
  const LazySimulatedScans scans(simulation, 0.1);
  const std::size_t from = 10;
  const std::size_t to = from + kLap;
  const Pose truth = relative(simulation.truth.poses[from], simulation.truth.poses[to]);
  const LoopCheck result =
      verifyLoop(scans, simulation.initial, {from, to, offsetBy(truth, 0.0, 4.0, 9.0)}, withSearch());
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_LT(translationError(result.relative, truth), kTranslationTolerance);
  EXPECT_LT(rotationErrorDeg(result.relative, truth), kRotationToleranceDeg);
}

}  // namespace
}  // namespace hba::closure
