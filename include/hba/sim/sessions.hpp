#pragma once
// Several sessions in one world: test data for multi-session mapping.
//
// Every session drives the same world (one seed for the terrain and the
// objects) along the same path (procedural loop or trajectory file), but its
// own stretch of it: session k starts k * shift metres further along than
// session 0 and, with `reverse`, the odd sessions drive the path the other
// way. Each has its own drift and sensor-noise streams, and its poses are in
// its OWN frame, the session's true first pose, as an odometry starting at
// its own origin would write them. Written as DIR/session-0, DIR/session-1 ...
// each a complete dataset (see simulation.hpp) plus:
//
//   gt_world.txt       ground truth in the common frame (session 0's own frame), TUM
//   session_frame.txt  the true pose of the session's frame in the common frame,
//                      one line: tx ty tz qx qy qz qw (gt_world = session_frame * gt)
#include <cstdint>
#include <filesystem>
#include <vector>

#include "hba/sim/simulation.hpp"

namespace hba::sim {

struct SessionsConfig {
  std::size_t count = 1;
  double shift = 50.0;   // m along the path between consecutive sessions' starts
  bool reverse = false;  // sessions 1, 3, 5 ... drive the path the other way
  // Frames of session k (missing entries: the base trajectory's frame count).
  std::vector<std::size_t> frames;
  // s from one session's last stamp to the next session's first, so that
  // stamps never coincide across sessions.
  double time_gap = 100.0;
};

// Throws hba::Error naming the setting for invalid values.
void validate(const SessionsConfig& config);

// Seed of session k's drift and sensor noise: session 0 keeps `seed`.
std::uint64_t sessionSeed(std::uint64_t seed, std::size_t session);

struct Session {
  std::size_t index = 0;
  std::uint64_t seed = 0;      // its drift and sensor-noise seed
  bool reversed = false;       // drives the path against session 0's direction
  double start_along = 0.0;    // m along the path from session 0's start
  Trajectory truth_simulator;  // true poses in the simulator's frame (for scanning)
  Pose common_from_session;    // the session's frame in the common frame
  Trajectory truth;            // in the session's frame: truth.poses[0] is the identity
  Trajectory truth_common;     // in the common frame (session 0's own frame)
  std::vector<Pose> initial;   // drifted, in the session's frame: initial[0] is the identity
};

struct SessionSet {
  SimulationConfig config;  // the base: world, path (trajectory.frames sizes a loop), sensor, drift
  SessionsConfig sessions;
  Terrain terrain{0, 0.0};
  World world;  // built around the span of the path every session drives
  std::vector<Session> list;
};

// Builds the shared world and every session's poses. Throws hba::Error.
SessionSet prepareSessions(const SimulationConfig& config, const SessionsConfig& sessions);
// Scan of frame `frame` of session `session` (downsampled if configured). Thread-safe.
PointCloud simulateSessionFrame(const SessionSet& set, std::size_t session, std::size_t frame);

// Name of session k's folder: "session-k".
std::string sessionFolderName(std::size_t session);

// Writes DIR/session-k for every session, all staged in one hidden folder and
// renamed into place when complete (see writeSimulation). The progress
// callback reports each session's frames in turn. Throws hba::Error.
void writeSessions(const SessionSet& set, const std::filesystem::path& output, const WriteOptions& options);

}  // namespace hba::sim
