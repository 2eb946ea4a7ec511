#include "hba/pipeline/prior_map.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "hba/ba/map_refinement.hpp"
#include "hba/core/error.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/pipeline/sessions.hpp"
#include "hba/voxel/downsample.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"

namespace hba::pipeline {
namespace {

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
closure::MapAlignment placeInMap(const PriorMap& map, const io::ScanSource& session,
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

PriorMap priorMapFromCloud(const std::filesystem::path& file) {
  PointCloud cloud = io::readScan(file);
  if (cloud.empty()) failAt(file, "holds no points: a map is a point cloud of the place");
  PriorMap map;
  map.cloud = voxel::downsample(cloud, kPriorMapVoxel, 4);
  map.name = file.string();
  return map;
}

PriorMap priorMapFromDataset(io::Dataset dataset, std::vector<Pose> poses, std::string name) {
  if (poses.size() != dataset.size()) {
    throw ValueError(name + ": " + std::to_string(poses.size()) + " poses for " +
                     std::to_string(dataset.size()) + " scans");
  }
  PriorMap map;
  map.poses = std::move(poses);
  eval::MapSettings settings;
  settings.voxel = kPriorMapVoxel;
  map.cloud = eval::buildMergedMap(io::DatasetScanSource(dataset), map.poses, settings);
  map.name = std::move(name);
  map.dataset.emplace(std::move(dataset));
  return map;
}

MapRun runInMap(const PriorMap& map, const io::ScanSource& scans, const std::vector<Pose>& poses,
                const HbaSettings& settings, const pipeline::ClosureInputs& closures,
                const std::string& session_name) {
  MapRun run;
  const voxel::DownsampledScanSource session(scans, settings.scan_voxel);
  run.alignment = placeInMap(map, session, poses, settings.scan_voxel);
  const closure::MapAlignment& a = run.alignment;
  run.alignment_report = alignmentReport(a, session_name);  // logs every pair with -v
  if (!a.found) {
    throw Error(session_name + ": could not place this session in the map " + map.name + " (" + a.reason +
                (map.dataset ? ""
                             : "; " + std::to_string(a.tiles) + " tiles of " +
                                   std::to_string(static_cast<int>(std::round(a.tile_radius_m))) + " m") +
                " in a map " + std::to_string(static_cast<long>(std::round(a.map_extent_m))) +
                " m across): is the map of this place, and in metres?");
  }
  spdlog::info("{}: placed in the map by {} agreeing of {} verified place-tile pairs ({} registered)",
               session_name, a.agreeing, a.verified, a.tried);
  for (const Pose& p : poses) run.placed.push_back(a.world_from_session * p);
  // The one refinement is the one against the map, below.
  HbaSettings alone = settings;
  alone.refine = false;
  run.result = pipeline::runHierarchicalBa(scans, run.placed, alone, closures);

  // Refined against the map: its planes pull the session onto them.
  const std::vector<PointCloud> clouds =
      loadAll(voxel::DownsampledScanSource(scans, settings.refine_scan_voxel));
  std::vector<const PointCloud*> pointers;
  for (const PointCloud& c : clouds) pointers.push_back(&c);
  const PointCloud near = voxel::downsample(ba::mapNear(map.cloud, run.result.poses, sensorReach(clouds)),
                                            settings.refine_scan_voxel, 4);
  const ba::RefinementResult refined =
      ba::refineAgainstMap(near, pointers, run.result.poses, settings.refinementBa());
  spdlog::info("refined against the map ({} of its points near the session): plane RMS {:.4f} -> {:.4f} m",
               near.size(), refined.rms_before, refined.rms_after);
  run.result.poses = refined.poses;
  run.map_points_near = near.size();
  run.plane_rms_before_m = refined.rms_before;
  run.plane_rms_after_m = refined.rms_after;
  return run;
}

std::vector<Pose> inMapFrame(const PriorMap& map, const std::vector<Pose>& poses) {
  const Pose to_map(Quat::Identity(), map.cloud.origin);
  std::vector<Pose> in_map;
  in_map.reserve(poses.size());
  for (const Pose& p : poses) in_map.push_back(to_map * p);
  return in_map;
}

nlohmann::json mapReport(const PriorMap& map, const MapRun& run) {
  nlohmann::json report = run.alignment_report;
  report["source"] = map.name;
  report["points"] = map.cloud.size();
  report["tiles"] = run.alignment.tiles;
  report["tile_radius_m"] = run.alignment.tile_radius_m;
  report["refinement"] = {{"map_points", run.map_points_near},
                          {"plane_rms_before_m", run.plane_rms_before_m},
                          {"plane_rms_after_m", run.plane_rms_after_m}};
  return report;
}

}  // namespace hba::pipeline
