// Writing several sessions: one dataset folder each, all staged together.
#include <array>
#include <charconv>
#include <string>

#include "core/staging_folder.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/sim/sessions.hpp"
#include "scan_writer.hpp"
#include "simulation_yaml.hpp"

namespace hba::sim {
namespace fs = std::filesystem;

namespace {

// session_frame.txt: one line "tx ty tz qx qy qz qw" (the TUM order without
// a stamp), shortest exact decimals as the pose files have them.
void writeSessionFrame(const fs::path& path, const Pose& pose) {
  const std::array<double, 7> values{pose.t.x(), pose.t.y(), pose.t.z(), pose.q.x(),
                                     pose.q.y(), pose.q.z(), pose.q.w()};
  writeFileAtomically(
      path,
      [&](std::ostream& out) {
        out << "# world_from_session: tx ty tz qx qy qz qw (gt_world = this * gt)\n";
        std::array<char, 32> buffer{};
        for (std::size_t i = 0; i < values.size(); ++i) {
          if (i > 0) out << ' ';
          const double value = values[i] == 0.0 ? 0.0 : values[i];  // never "-0"
          const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
          out.write(buffer.data(), result.ptr - buffer.data());
        }
        out << '\n';
      },
      false);
}

void writeSessionYaml(const SessionSet& set, const Session& session, const fs::path& path) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  emitYamlHeader(out, set.config.seed);
  out << YAML::Key << "files" << YAML::Value << YAML::BeginMap;
  emitDatasetFiles(out);
  out << YAML::Key << "ground_truth_world" << YAML::Value
      << "gt_world.txt (tum, in session 0's frame, the common world frame)";
  out << YAML::Key << "session_frame" << YAML::Value
      << "session_frame.txt (world_from_session: tx ty tz qx qy qz qw)";
  out << YAML::EndMap;
  out << YAML::Key << "session" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "index" << YAML::Value << session.index;
  out << YAML::Key << "sessions" << YAML::Value << set.sessions.count;
  out << YAML::Key << "shift_m" << YAML::Value << set.sessions.shift;
  out << YAML::Key << "start_along_path_m" << YAML::Value << session.start_along;
  out << YAML::Key << "reversed" << YAML::Value << session.reversed;
  out << YAML::Key << "seed" << YAML::Value << session.seed;
  out << YAML::Key << "first_stamp_s" << YAML::Value << session.truth.stamps.front();
  out << YAML::Key << "time_gap_s" << YAML::Value << set.sessions.time_gap;
  out << YAML::EndMap;
  emitYamlBody(out, set.config, session.truth.poses, set.world);
  out << YAML::EndMap;
  writeYamlFile(path, out);
}

// The small files last: even inside the staging folder, a session without
// pose.json does not look complete.
void writeSessionPoseFiles(const SessionSet& set, const Session& session, const fs::path& dir) {
  io::writePoses(dir / "gt.txt", session.truth, io::PoseFormat::Tum);
  io::writePoses(dir / "gt_world.txt", session.truth_common, io::PoseFormat::Tum);
  writeSessionFrame(dir / "session_frame.txt", session.common_from_session);
  io::writeTimes(dir / "times.txt", session.truth.stamps);
  writeSessionYaml(set, session, dir / "sim.yaml");
  Trajectory initial;
  initial.poses = session.initial;
  initial.stamps = session.truth.stamps;
  io::writePoses(dir / "pose.json", initial, io::PoseFormat::Hba);
}

}  // namespace

void writeSessions(const SessionSet& set, const fs::path& output, const WriteOptions& options) {
  StagingFolder staging(output, options.force);
  for (const Session& session : set.list) {
    const fs::path dir = staging.path() / sessionFolderName(session.index);
    fs::create_directory(dir);
    if (!options.poses_only) {
      writeScans(
          session.truth.size(), [&](std::size_t k) { return simulateSessionFrame(set, session.index, k); },
          dir / "pcd", options);
    }
    writeSessionPoseFiles(set, session, dir);
  }
  staging.commit();
}

}  // namespace hba::sim
