// `hba optimize NEW --map MAP -o OUT` and `--fixed SESSION`: a new session
// placed in a map that stays put, optimized, then refined against the map's
// planes; the poses come out in the map's frame (docs/closure.md).
#include <spdlog/spdlog.h>

#include <optional>

#include "core/input_file.hpp"
#include "core/staging_folder.hpp"
#include "earlier_output.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/pipeline/prior_map.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "memory_check.hpp"
#include "optimize_parts.hpp"
#include "output_dir.hpp"

namespace hba::cli::optimize {
namespace {
namespace fs = std::filesystem;

// An earlier `hba optimize` output: its input's scans, read as that run read
// them (a recording's keyframes), at its optimized poses.
pipeline::PriorMap readEarlierOutput(const fs::path& folder) {
  if (!isOptimizeOutput(folder)) {
    failAt(folder,
           "is a folder but not an hba optimize output (no report.json and pose.json): give a map file "
           "(" +
               io::scanFormatList(true) + ") or --fixed DATASET");
  }
  const nlohmann::json report = readOutputReport(folder);
  if (outputInputFlag(report, folder, "scans_in_world")) {
    failAt(folder,
           "was made from scans saved in the world frame: write its map with hba map and give that file");
  }
  io::Dataset dataset = openEarlierDataset(report, folder, DatasetArgs());
  std::vector<Pose> poses = earlierPoses(dataset, report, folder);
  // Raw sweeps: deskewed by the motion the run found, as the run last did.
  if (dataset.pointTimes()) dataset.deskewBy(poses);
  std::string name = folder.string() + " (" + dataset.root().string() + " at its optimized poses)";
  return pipeline::priorMapFromDataset(std::move(dataset), std::move(poses), std::move(name));
}

pipeline::PriorMap readFixedMap(const Args& args) {
  if (!args.fixed.empty()) {
    DatasetArgs fixed;
    fixed.dir = args.fixed;
    io::Dataset dataset = fixed.open();
    std::vector<Pose> poses = dataset.trajectory().poses;
    return pipeline::priorMapFromDataset(std::move(dataset), std::move(poses),
                                         args.fixed + " (its scans at its poses)");
  }
  const fs::path path = args.map;
  if (fs::is_directory(path)) return readEarlierOutput(path);
  return pipeline::priorMapFromCloud(path);
}

}  // namespace

void runWithMap(const Args& args, HbaSettings settings) {
  if (!args.more_sessions.empty()) {
    throw Error(
        "--map and --fixed take one new session: give the others as the map, or run them as sessions "
        "without --map");
  }
  if (!args.map.empty() && !args.fixed.empty()) throw Error("give --map MAP or --fixed SESSION, not both");
  if (!args.closure_files.priors.empty()) {
    throw Error("--priors with --map: the map fixes the frame the poses come out in; give one or the other");
  }
  std::error_code ec;
  if (!args.fixed.empty() && (args.fixed == args.data.dir || fs::equivalent(args.fixed, args.data.dir, ec))) {
    throw ValueError("--fixed " + args.fixed + " is the session being optimized (" + args.data.dir +
                     "): a session placed in a map of itself finds only itself; give the map of another "
                     "session, or optimize " +
                     args.data.dir + " alone");
  }
  io::Dataset dataset = args.data.open();
  refuseOutputInsideInput(args.output, dataset);
  const pipeline::PriorMap map = readFixedMap(args);
  spdlog::info("map {}: {} points at {} m", map.name, map.cloud.size(), pipeline::kPriorMapVoxel);
  const pipeline::ClosureInputs closures = readClosureInputs(args, {&dataset}, {0}, dataset.size());
  const io::DatasetScanSource scans(dataset);
  const nlohmann::json memory = checkMemory(pipeline::planRun(scans, settings), args.no_memory_check);

  StagingFolder staging(args.output, args.force, "hba optimize");
  announceReplacement(staging);
  const fs::path& out = staging.path();
  const nlohmann::json conventions =
      checkConventions(args, voxel::DownsampledScanSource(scans, settings.scan_voxel), dataset);
  const pipeline::MapRun run =
      pipeline::runInMap(map, scans, dataset.trajectory().poses, settings, closures, args.data.dir);
  const pipeline::HbaResult& result = run.result;
  const std::vector<Pose> in_map = pipeline::inMapFrame(map, result.poses);
  writeOptimizedPoses(out, dataset, in_map);
  nlohmann::json report = reportJson(result, dataset, args.data, settings, conventions);
  report["memory_estimate"] = memory;
  report["map"] = pipeline::mapReport(map, run);
  report = writeReport(out, report);
  const bool drawn =
      !args.no_render && writePicture(scans, result, settings.scan_voxel, run.placed, std::nullopt, out);
  const bool paged =
      !args.no_report_page && writeReportPage(scans, result, settings.scan_voxel, run.placed, std::nullopt,
                                              report, folderName(dataset.root()), out);
  staging.commit();
  spdlog::info("done: {} (poses in the map's frame, report.json{}{})", staging.destination().string(),
               drawn ? ", before_after.png" : "", paged ? ", report.html" : "");
}

}  // namespace hba::cli::optimize
