// Several sessions in one world: each in its own frame, placed where the
// shift along the shared path puts it, scanning the same world.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/sim/sessions.hpp"
#include "session_test_support.hpp"

namespace hba::sim {
namespace {

using test::nearestNeighbourMedian;
using test::posesNear;

// Two sessions of a 120-frame block tour (a 100 m lap): session 1 starts
// 20 m (40 frames) further along, so they share 40 m of road.
constexpr double kShift = 20.0;
constexpr std::size_t kShiftFrames = 40;  // kShift / 0.5 m per frame

SimulationConfig baseConfig() {
  SimulationConfig config;
  config.seed = 5;
  config.trajectory.frames = 120;
  return config;
}

const SessionSet& twoSessions(bool reverse) {
  static const SessionSet forward = [] {
    SessionsConfig sessions;
    sessions.count = 2;
    sessions.shift = kShift;
    return prepareSessions(baseConfig(), sessions);
  }();
  static const SessionSet backward = [] {
    SessionsConfig sessions;
    sessions.count = 2;
    sessions.shift = kShift;
    sessions.reverse = true;
    return prepareSessions(baseConfig(), sessions);
  }();
  return reverse ? backward : forward;
}

TEST(SimSessions, EachSessionStartsAtTheIdentityOfItsOwnFrame) {
  for (bool reverse : {false, true}) {
    for (const Session& session : twoSessions(reverse).list) {
      ASSERT_EQ(session.truth.size(), 120u);
      EXPECT_EQ(session.truth.poses[0].t, Vec3::Zero());
      EXPECT_EQ(session.truth.poses[0].q.coeffs(), Quat::Identity().coeffs());
      EXPECT_EQ(session.initial[0].t, Vec3::Zero());
      EXPECT_EQ(session.initial[0].q.coeffs(), Quat::Identity().coeffs());
      // The common frame is the session's frame moved by its world_from_session.
      for (std::size_t k = 0; k < session.truth.size(); ++k) {
        EXPECT_TRUE(posesNear(session.truth_common.poses[k],
                              session.common_from_session * session.truth.poses[k], 1e-9));
      }
    }
    const Session& first = twoSessions(reverse).list[0];
    EXPECT_TRUE(posesNear(first.common_from_session, Pose::identity(), 0.0));
  }
}

TEST(SimSessions, SecondSessionStartsWhereTheShiftAlongTheFirstLeads) {
  const Session& first = twoSessions(false).list[0];
  const Session& second = twoSessions(false).list[1];
  // Driving 20 m along session 0 reaches session 1's start: same place, same heading.
  EXPECT_TRUE(posesNear(second.common_from_session, first.truth.poses[kShiftFrames], 1e-6));
  // And both then drive the same road: frame k of session 1 is frame k + 40 of session 0.
  for (std::size_t k = 0; k + kShiftFrames < first.truth.size(); k += 10) {
    EXPECT_TRUE(posesNear(second.truth_common.poses[k], first.truth_common.poses[k + kShiftFrames], 1e-6))
        << k;
  }
  // The 100 m lap is a rounded rectangle 32.2 x 21.5 m (corner radius 4.3 m)
  // started mid bottom edge: 20 m along is 1.4 m up its right edge, heading
  // north, 17.1 m from the start.
  const Pose& frame = second.common_from_session;
  EXPECT_NEAR(std::atan2(frame.R()(1, 0), frame.R()(0, 0)) * 180.0 / M_PI, 90.0, 1.0);
  EXPECT_NEAR(frame.t.norm(), 17.1, 0.3);
}

TEST(SimSessions, ReversedSessionDrivesTheSameRoadTheOtherWay) {
  const Session& first = twoSessions(true).list[0];
  const Session& second = twoSessions(true).list[1];
  EXPECT_FALSE(first.reversed);
  EXPECT_TRUE(second.reversed);
  // It starts where the forward one would and drives back towards session 0's start.
  for (std::size_t k = 0; k <= kShiftFrames; k += 10) {
    const Pose& mine = second.truth_common.poses[k];
    const Pose& theirs = first.truth_common.poses[kShiftFrames - k];
    EXPECT_LT((mine.t - theirs.t).norm(), 1e-6) << k;
    // Heading turned by half a turn (the x axes are opposed).
    EXPECT_NEAR(mine.R().col(0).dot(theirs.R().col(0)), -1.0, 1e-3) << k;
  }
}

TEST(SimSessions, SessionsScanTheSameWorld) {
  const SessionSet& set = twoSessions(false);
  const Session& first = set.list[0];
  const Session& second = set.list[1];
  // Two frames 2 m apart on the shared road: other rays, other noise, the same surfaces.
  const std::size_t best_first = kShiftFrames + 4, best_second = 0;
  ASSERT_NEAR((first.truth_common.poses[best_first].t - second.truth_common.poses[best_second].t).norm(), 2.0,
              0.1);
  // In the world with their gt_world poses, the two scans lie on the same
  // surfaces: point-to-plane distances below the range noise (sigma 0.02 m).
  const PointCloud a = simulateSessionFrame(set, 0, best_first);
  const PointCloud b = simulateSessionFrame(set, 1, best_second);
  const double aligned = nearestNeighbourMedian(a, first.truth_common.poses[best_first], b,
                                                second.truth_common.poses[best_second]);
  EXPECT_LT(aligned, 0.02);
  // A 10 cm error in the common frame is plainly visible: the test can fail.
  Pose shifted = second.truth_common.poses[best_second];
  shifted.t += Vec3(0.06, 0.06, 0.06);
  EXPECT_GT(nearestNeighbourMedian(a, first.truth_common.poses[best_first], b, shifted), 3.0 * aligned);
}

TEST(SimSessions, SessionsHaveTheirOwnDriftNoiseAndStamps) {
  const SessionSet& set = twoSessions(false);
  const Session& first = set.list[0];
  const Session& second = set.list[1];
  EXPECT_EQ(first.seed, 5u);  // session 0 keeps the seed
  EXPECT_NE(second.seed, first.seed);
  // The same true pose scanned by both: other noise and dropout, other points.
  ASSERT_TRUE(posesNear(second.truth_simulator.poses[0], first.truth_simulator.poses[kShiftFrames], 1e-9));
  EXPECT_NE(simulateSessionFrame(set, 0, kShiftFrames).points, simulateSessionFrame(set, 1, 0).points);
  // Their own drift streams: the errors after 30 m differ.
  const Vec3 error_first = first.initial[60].t - first.truth.poses[60].t;
  const Vec3 error_second = second.initial[60].t - second.truth.poses[60].t;
  EXPECT_GT((error_first - error_second).norm(), 0.01);
  // 1 % drift over 30 m: errors of decimetres, not metres.
  EXPECT_LT(error_first.norm(), 1.5);
  EXPECT_LT(error_second.norm(), 1.5);
  // Stamps: session 1 starts 100 s after session 0's last frame.
  EXPECT_EQ(first.truth.stamps.front(), 0.0);
  EXPECT_NEAR(second.truth.stamps.front(), first.truth.stamps.back() + 0.1 + 100.0, 1e-9);
  EXPECT_NEAR(second.truth.stamps[1] - second.truth.stamps[0], 0.1, 1e-9);
}

TEST(SimSessions, FrameCountsArePerSession) {
  SimulationConfig config = baseConfig();
  config.trajectory.frames = 20;
  SessionsConfig sessions;
  sessions.count = 3;
  sessions.shift = 4.0;
  sessions.frames = {20, 8};  // session 2: the base count
  const SessionSet set = prepareSessions(config, sessions);
  ASSERT_EQ(set.list.size(), 3u);
  EXPECT_EQ(set.list[0].truth.size(), 20u);
  EXPECT_EQ(set.list[1].truth.size(), 8u);
  EXPECT_EQ(set.list[2].truth.size(), 20u);
  EXPECT_TRUE(posesNear(set.list[2].common_from_session, set.list[0].truth.poses[16], 1e-6));
}

TEST(SimSessions, RejectsBadSettingsNamingThem) {
  const auto message = [](const SessionsConfig& sessions) {
    try {
      validate(sessions);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SessionsConfig none;
  none.count = 0;
  EXPECT_NE(message(none).find("--sessions"), std::string::npos) << message(none);
  SessionsConfig backwards;
  backwards.shift = -5.0;
  EXPECT_NE(message(backwards).find("--session-shift"), std::string::npos) << message(backwards);
  backwards.shift = std::nan("");
  EXPECT_NE(message(backwards).find("--session-shift"), std::string::npos) << message(backwards);
  SessionsConfig empty;
  empty.frames = {10, 0};
  EXPECT_NE(message(empty).find("session 1 has 0 frames"), std::string::npos) << message(empty);
  EXPECT_THROW(prepareSessions(baseConfig(), none), Error);
}

}  // namespace
}  // namespace hba::sim
