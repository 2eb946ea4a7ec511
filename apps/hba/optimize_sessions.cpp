// `hba optimize A B ... -o OUT`: several sessions of one place, each in its
// own frame, optimized as one sequence into one map in A's frame.
#include <spdlog/spdlog.h>

#include <sstream>

#include "core/input_file.hpp"
#include "core/staging_folder.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/pipeline/sessions.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "memory_check.hpp"
#include "optimize_parts.hpp"
#include "output_dir.hpp"

namespace hba::cli::optimize {
namespace {
namespace fs = std::filesystem;

void refuseOverrides(const DatasetArgs& d) {
  if (!d.scans.empty() || !d.poses.empty() || !d.format.empty() || !d.times.empty() || !d.extrinsic.empty() ||
      !d.calibration.empty() || d.invert_poses || d.scans_in_world) {
    throw Error(
        "--scans, --poses, --format, --times and the convention flags name one dataset's files: with "
        "several sessions, give each session as a folder that hba finds on its own");
  }
}

// --align FILE: one "tx ty tz qx qy qz qw" line per later session.
std::vector<Pose> readAlignmentFile(const fs::path& path, std::size_t later_sessions) {
  std::istringstream in(readTextFile(path));
  std::vector<Pose> transforms;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    transforms.push_back(parsePoseArgument(line, path.string()));
  }
  if (transforms.size() != later_sessions) {
    failAt(path, "holds " + std::to_string(transforms.size()) + " transforms for " +
                     std::to_string(later_sessions) +
                     " later sessions (one 'tx ty tz qx qy qz qw' line each)");
  }
  return transforms;
}

std::string sessionName(std::size_t k) { return "session-" + std::to_string(k); }

// One session given twice (`optimize A A`, or A and a link to it) would be
// matched against itself, every scan twice: refused before any work.
void refuseRepeatedSessions(const std::vector<std::string>& dirs) {
  for (std::size_t k = 1; k < dirs.size(); ++k) {
    for (std::size_t j = 0; j < k; ++j) {
      std::error_code ec;
      if (dirs[j] == dirs[k] || fs::equivalent(dirs[j], dirs[k], ec)) {
        throw ValueError(dirs[k] + ": this session is given twice (sessions " + std::to_string(j) + " and " +
                         std::to_string(k) + (dirs[j] == dirs[k] ? "" : ", as " + dirs[j]) +
                         "); give each session once");
      }
    }
  }
}

}  // namespace

void runSessions(const Args& args, HbaSettings settings) {
  refuseOverrides(args.data);
  std::vector<std::string> dirs{args.data.dir};
  dirs.insert(dirs.end(), args.more_sessions.begin(), args.more_sessions.end());
  refuseRepeatedSessions(dirs);
  std::vector<io::Dataset> datasets;
  for (const std::string& dir : dirs) {
    DatasetArgs one = args.data;
    one.dir = dir;
    datasets.push_back(one.open());
    refuseOutputInsideInput(args.output, datasets.back());
  }
  std::vector<const io::Dataset*> sessions_in;
  for (const io::Dataset& d : datasets) sessions_in.push_back(&d);
  const pipeline::SessionScans session_scans(sessions_in, dirs);
  const io::ConcatenatedScanSource& scans = session_scans.all();
  pipeline::ClosureInputs closures = readClosureInputs(args, sessions_in, scans.starts(), scans.size());
  const std::optional<Trajectory> gt = readGroundTruth(args, datasets[0], scans.size());
  const pipeline::Plan plan = pipeline::planRun(scans, settings);
  const nlohmann::json memory = checkMemory(plan, args.no_memory_check);

  StagingFolder staging(args.output, args.force, "hba optimize");
  announceReplacement(staging);
  const fs::path& out = staging.path();
  nlohmann::json conventions = nlohmann::json::array();
  for (std::size_t k = 0; k < datasets.size(); ++k) {
    conventions.push_back(checkConventions(
        args, voxel::DownsampledScanSource(*session_scans.inputs()[k].scans, settings.scan_voxel),
        datasets[k]));
  }

  // Each later session placed in the first one's frame, then one run.
  pipeline::SessionPlacement how;
  if (args.align == "identity") {
    how.method = pipeline::SessionPlacement::Method::Identity;
  } else if (args.align != "register") {
    how.method = pipeline::SessionPlacement::Method::Given;
    how.given = readAlignmentFile(args.align, datasets.size() - 1);
  }
  const pipeline::SessionsRun run = pipeline::runSessions(session_scans, how, plan, closures);
  const pipeline::PlacedSessions& placed = run.placed;
  const pipeline::HbaResult& result = run.result;
  const std::vector<Pose>& initial = run.initial;

  nlohmann::json sessions = nlohmann::json::array();
  for (std::size_t k = 0; k < datasets.size(); ++k) {
    const std::size_t first = scans.starts()[k], end = scans.starts()[k + 1];
    const std::vector<Pose> poses(result.poses.begin() + static_cast<std::ptrdiff_t>(first),
                                  result.poses.begin() + static_cast<std::ptrdiff_t>(end));
    const fs::path folder = out / sessionName(k);
    fs::create_directories(folder);
    writeOptimizedPoses(folder, datasets[k], poses);
    // Where the session's own frame ended up: its first pose, optimized, over its input.
    const Pose world_from_session = poses.front() * datasets[k].trajectory().poses.front().inverse();
    writeFileAtomically(
        folder / "session_frame.txt",
        [&](std::ostream& os) {
          os.precision(17);
          os << "# world_from_session (the first session's frame): tx ty tz qx qy qz qw\n"
             << world_from_session.t.x() << ' ' << world_from_session.t.y() << ' ' << world_from_session.t.z()
             << ' ' << world_from_session.q.x() << ' ' << world_from_session.q.y() << ' '
             << world_from_session.q.z() << ' ' << world_from_session.q.w() << '\n';
        },
        false);
    sessions.push_back({{"name", sessionName(k)},
                        {"input", fs::absolute(datasets[k].root()).string()},
                        {"first_frame", first},
                        {"frames", end - first}});
  }
  nlohmann::json report = reportJson(result, datasets[0], args.data, settings, conventions);
  report["sessions"] = sessions;
  report["memory_estimate"] = memory;
  report["alignment"] = {{"method", pipeline::placementName(how.method)}, {"registered", placed.registered}};
  report = writeReport(out, report);
  const bool drawn = !args.no_render && writePicture(scans, result, settings.scan_voxel, initial, gt, out);
  const bool paged = !args.no_report_page && writeReportPage(scans, result, settings.scan_voxel, initial, gt,
                                                             report, folderName(datasets[0].root()), out);
  staging.commit();
  spdlog::info("done in {:.1f} s: {} ({} session folders, report.json{}{})", result.report.seconds_total,
               staging.destination().string(), datasets.size(), drawn ? ", before_after.png" : "",
               paged ? ", report.html" : "");
}

}  // namespace hba::cli::optimize
