// Preparing several sessions in one world: their stretches of the shared
// path, their frames, stamps and drift, and the world around all of them.
#include "hba/sim/sessions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hba/core/error.hpp"
#include "hba/voxel/downsample.hpp"
#include "shared_path.hpp"
#include "sim/random.hpp"

namespace hba::sim {
namespace {

// More would be a typing mistake, not a data set.
constexpr std::size_t kMaxSessions = 1000;

std::size_t framesOf(const SimulationConfig& config, const SessionsConfig& sessions, std::size_t k) {
  return k < sessions.frames.size() ? sessions.frames[k] : config.trajectory.frames;
}

// Re-expresses the session's true poses in its own frame (its first pose)
// and in the common frame, and drifts them from its own origin.
void setFrames(Session& session, const Pose& common_from_simulator, const DriftConfig& drift) {
  const Pose session_in_simulator = session.truth_simulator.poses.front();
  const Pose session_from_simulator = session_in_simulator.inverse();
  session.common_from_session =
      session.index == 0 ? Pose::identity() : common_from_simulator * session_in_simulator;
  session.truth.stamps = session.truth_simulator.stamps;
  session.truth_common.stamps = session.truth_simulator.stamps;
  for (const Pose& pose : session.truth_simulator.poses) {
    // The first pose is the frame itself: exactly the identity, not a rounding of it.
    const Pose in_session = session.truth.empty() ? Pose::identity() : session_from_simulator * pose;
    session.truth.poses.push_back(in_session);
    // Session 0's frame is the common frame: the same poses, not a product with the identity.
    session.truth_common.poses.push_back(session.index == 0 ? in_session
                                                            : session.common_from_session * in_session);
  }
  session.initial = applyDrift(session.truth.poses, drift, session.seed);
}

}  // namespace

void validate(const SessionsConfig& config) {
  if (config.count == 0 || config.count > kMaxSessions) {
    throw Error("simulate: the number of sessions (--sessions) must be in [1, " +
                std::to_string(kMaxSessions) + "], got " + std::to_string(config.count));
  }
  if (!std::isfinite(config.shift) || config.shift < 0.0) {
    throw Error("simulate: the shift between sessions (--session-shift) must be a distance >= 0 m, got " +
                std::to_string(config.shift));
  }
  for (std::size_t k = 0; k < config.frames.size(); ++k) {
    if (config.frames[k] == 0) {
      throw Error("simulate: session " + std::to_string(k) +
                  " has 0 frames (--session-frames must be positive)");
    }
  }
  if (!std::isfinite(config.time_gap) || config.time_gap < 0.0) {
    throw Error("simulate: the time gap between sessions must be >= 0 s");
  }
}

std::uint64_t sessionSeed(std::uint64_t seed, std::size_t session) {
  if (session == 0) return seed;
  return mix64(mix64(seed ^ mix64(static_cast<std::uint64_t>(Stream::Session))) + session);
}

std::string sessionFolderName(std::size_t session) { return "session-" + std::to_string(session); }

SessionSet prepareSessions(const SimulationConfig& config, const SessionsConfig& sessions) {
  validate(config);
  validate(sessions);
  SessionSet set;
  set.config = config;
  set.sessions = sessions;
  set.terrain = Terrain(config.seed, config.world.max_slope);
  const SharedPath path(config.trajectory);
  const TrajectoryConfig& t = config.trajectory;

  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  double first_stamp = 0.0;
  for (std::size_t k = 0; k < sessions.count; ++k) {
    Session session;
    session.index = k;
    session.seed = sessionSeed(config.seed, k);
    session.reversed = sessions.reverse && k % 2 == 1;
    session.start_along = static_cast<double>(k) * sessions.shift;
    const PathStretch stretch =
        path.stretch(session.start_along, framesOf(config, sessions, k), session.reversed);
    if (stretch.path.positions.size() < 2) {
      throw Error("simulate: session " + std::to_string(k) +
                  " has fewer than 2 frames left on the trajectory file (lower --session-shift)");
    }
    low = std::min(low, stretch.low);
    high = std::max(high, stretch.high);
    session.truth_simulator = drapeOnTerrain(stretch.path, set.terrain, t.sensor_height, t.frame_rate_hz);
    for (double& stamp : session.truth_simulator.stamps) stamp += first_stamp;
    first_stamp = session.truth_simulator.stamps.back() + 1.0 / t.frame_rate_hz + sessions.time_gap;
    set.list.push_back(std::move(session));
  }

  const Pose common_from_simulator = set.list.front().truth_simulator.poses.front().inverse();
  for (Session& session : set.list) setFrames(session, common_from_simulator, config.drift);

  // One world around everything any session drives, so that it is the same
  // world for all and every session keeps its free corridor.
  const Trajectory span = drapeOnTerrain(path.span(low, high), set.terrain, t.sensor_height, t.frame_rate_hz);
  set.world = buildWorld(span.poses, set.terrain, config.world, config.seed);
  return set;
}

PointCloud simulateSessionFrame(const SessionSet& set, std::size_t session, std::size_t frame) {
  const Session& s = set.list.at(session);
  const PointCloud cloud =
      scan(set.world, s.truth_simulator.poses.at(frame), set.config.sensor, s.seed, frame);
  return voxel::downsample(cloud, set.config.downsample_voxel);
}

}  // namespace hba::sim
