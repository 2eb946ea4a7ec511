// `hba optimize NEW --map MAP -o OUT` and `--fixed SESSION`: a new session
// placed in a map that stays put, optimized, then refined against the map's
// planes; the poses come out in the map's frame (docs/closure.md).
#include <spdlog/spdlog.h>

#include <optional>

#include "core/input_file.hpp"
#include "core/staging_folder.hpp"
#include "earlier_output.hpp"
#include "hba/ba/map_refinement.hpp"
#include "hba/closure/map_alignment.hpp"
#include "hba/core/error.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/pyramid/sessions.hpp"
#include "hba/voxel/downsample.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "memory_check.hpp"
#include "optimize_parts.hpp"
#include "output_dir.hpp"

namespace hba::cli::optimize {
namespace {
namespace fs = std::filesystem;

constexpr double kMapVoxel = 0.1;  // m: the map is held at this spacing

struct FixedMap {
  PointCloud cloud;  // relative to cloud.origin
  std::string name;  // for messages and the report
  // When the map is a dataset at its poses: the session is placed by its
  // places (each locally consistent) rather than by tiles of the merged
  // cloud, which carry whatever drift the poses have.
  std::optional<io::Dataset> dataset;
  std::vector<Pose> poses;
};

FixedMap datasetMap(io::Dataset dataset, std::vector<Pose> poses, std::string name) {
  FixedMap map;
  map.poses = std::move(poses);
  eval::MapSettings settings;
  settings.voxel = kMapVoxel;
  map.cloud = eval::buildMergedMap(io::DatasetScanSource(dataset), map.poses, settings);
  map.name = std::move(name);
  map.dataset.emplace(std::move(dataset));
  return map;
}

// An earlier `hba optimize` output: its input's scans, read as that run read
// them (a recording's keyframes), at its optimized poses.
FixedMap readEarlierOutput(const fs::path& folder) {
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
  return datasetMap(std::move(dataset), std::move(poses), std::move(name));
}

FixedMap readFixedMap(const Args& args) {
  if (!args.fixed.empty()) {
    DatasetArgs fixed;
    fixed.dir = args.fixed;
    io::Dataset dataset = fixed.open();
    std::vector<Pose> poses = dataset.trajectory().poses;
    return datasetMap(std::move(dataset), std::move(poses), args.fixed + " (its scans at its poses)");
  }
  const fs::path path = args.map;
  if (fs::is_directory(path)) return readEarlierOutput(path);
  PointCloud cloud = io::readScan(path);
  if (cloud.empty()) failAt(path, "holds no points: a map is a point cloud of the place");
  FixedMap map;
  map.cloud = voxel::downsample(cloud, kMapVoxel, 4);
  map.name = path.string();
  return map;
}

std::vector<PointCloud> loadAll(const io::ScanSource& scans) {
  std::vector<PointCloud> clouds(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) clouds[i] = scans.load(i);
  return clouds;
}

// The farthest a scan's point lies from its sensor: what of the map the session can see.
double sensorReach(const std::vector<PointCloud>& clouds) {
  double reach = 0.0;
  for (const PointCloud& cloud : clouds) {
    for (const Vec3f& p : cloud.points) reach = std::max(reach, static_cast<double>(p.norm()));
  }
  return std::max(reach, 1.0);
}

// The session's frame in the map's point coordinates (relative to its origin).
closure::MapAlignment placeInMap(const FixedMap& map, const io::ScanSource& session,
                                 const std::vector<Pose>& poses, double scan_voxel) {
  const closure::SessionAlignmentSettings settings;
  if (!map.dataset) return closure::alignToMap(map.cloud, session, poses, settings);
  const io::DatasetScanSource scans(*map.dataset);
  const voxel::DownsampledScanSource reference(scans, scan_voxel);
  closure::MapAlignment a;
  static_cast<closure::SessionAlignment&>(a) =
      closure::alignSession(reference, map.poses, session, poses, settings);
  for (const Vec3f& p : map.cloud.points)
    a.map_extent_m = std::max(a.map_extent_m, 2.0 * p.cast<double>().norm());
  a.world_from_session = Pose(Quat::Identity(), -map.cloud.origin) * a.world_from_session;
  return a;
}

}  // namespace

void runWithMap(const Args& args, pyramid::HbaSettings settings) {
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
  const FixedMap map = readFixedMap(args);
  spdlog::info("map {}: {} points at {} m", map.name, map.cloud.size(), kMapVoxel);
  const pyramid::ClosureInputs closures = readClosureInputs(args, {&dataset}, {0}, dataset.size());
  const io::DatasetScanSource scans(dataset);
  const nlohmann::json memory = checkMemory(scans, settings, args.no_memory_check);

  StagingFolder staging(args.output, args.force, "hba optimize");
  announceReplacement(staging);
  const fs::path& out = staging.path();
  const voxel::DownsampledScanSource session(scans, settings.scan_voxel);
  const nlohmann::json conventions = checkConventions(args, session, dataset);

  const closure::MapAlignment a = placeInMap(map, session, dataset.trajectory().poses, settings.scan_voxel);
  nlohmann::json map_report = pyramid::alignmentReport(a, args.data.dir);  // logs every pair with -v
  if (!a.found) {
    throw Error(args.data.dir + ": could not place this session in the map " + map.name + " (" + a.reason +
                (map.dataset ? ""
                             : "; " + std::to_string(a.tiles) + " tiles of " +
                                   std::to_string(static_cast<int>(std::round(a.tile_radius_m))) + " m") +
                " in a map " + std::to_string(static_cast<long>(std::round(a.map_extent_m))) +
                " m across): is the map of this place, and in metres?");
  }
  spdlog::info("{}: placed in the map by {} agreeing of {} verified place-tile pairs ({} registered)",
               args.data.dir, a.agreeing, a.verified, a.tried);
  std::vector<Pose> placed;
  for (const Pose& p : dataset.trajectory().poses) placed.push_back(a.world_from_session * p);
  // The one refinement is the one against the map, below.
  pyramid::HbaSettings alone = settings;
  alone.refine = false;
  pyramid::HbaResult result = pyramid::runHierarchicalBa(scans, placed, alone, closures);

  // Refined against the map: its planes pull the session onto them.
  const std::vector<PointCloud> clouds =
      loadAll(voxel::DownsampledScanSource(scans, settings.refine_scan_voxel));
  std::vector<const PointCloud*> pointers;
  for (const PointCloud& c : clouds) pointers.push_back(&c);
  const PointCloud near = voxel::downsample(ba::mapNear(map.cloud, result.poses, sensorReach(clouds)),
                                            settings.refine_scan_voxel, 4);
  const ba::RefinementResult refined =
      ba::refineAgainstMap(near, pointers, result.poses, settings.refinementBa());
  spdlog::info("refined against the map ({} of its points near the session): plane RMS {:.4f} -> {:.4f} m",
               near.size(), refined.rms_before, refined.rms_after);
  result.poses = refined.poses;

  const Pose to_map(Quat::Identity(), map.cloud.origin);
  std::vector<Pose> in_map;
  for (const Pose& p : result.poses) in_map.push_back(to_map * p);
  writeOptimizedPoses(out, dataset, in_map);
  nlohmann::json report = reportJson(result, dataset, args.data, settings, conventions);
  report["memory_estimate"] = memory;
  map_report["source"] = map.name;
  map_report["points"] = map.cloud.size();
  map_report["tiles"] = a.tiles;
  map_report["tile_radius_m"] = a.tile_radius_m;
  map_report["refinement"] = {{"map_points", near.size()},
                              {"plane_rms_before_m", refined.rms_before},
                              {"plane_rms_after_m", refined.rms_after}};
  report["map"] = map_report;
  report = writeReport(out, report);
  const bool drawn =
      !args.no_render && writePicture(scans, result, settings.scan_voxel, placed, std::nullopt, out);
  const bool paged =
      !args.no_report_page && writeReportPage(scans, result, settings.scan_voxel, placed, std::nullopt,
                                              report, folderName(dataset.root()), out);
  staging.commit();
  spdlog::info("done: {} (poses in the map's frame, report.json{}{})", staging.destination().string(),
               drawn ? ", before_after.png" : "", paged ? ", report.html" : "");
}

}  // namespace hba::cli::optimize
