#pragma once
// A new session placed in a map that stays put, optimized, then refined
// against the map's planes, its poses in the map's frame (docs/closure.md,
// "A prior map"). `hba optimize NEW --map MAP` / `--fixed SESSION` and
// hba.optimize_in_map make the same calls: a PriorMap, runInMap, inMapFrame.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hba/closure/map_alignment.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"

namespace hba::pipeline {

inline constexpr double kPriorMapVoxel = 0.1;  // m: the map is held at this spacing

struct PriorMap {
  PointCloud cloud;  // at kPriorMapVoxel, relative to cloud.origin
  std::string name;  // for messages and the report
  // When the map is a dataset at its poses: the session is placed by its
  // places (each locally consistent) rather than by tiles of the merged
  // cloud, which carry whatever drift the poses have.
  std::optional<io::Dataset> dataset;
  std::vector<Pose> poses;
};

// A map cloud file (any scan format). Throws hba::Error naming the file when
// it cannot be read or holds no points.
PriorMap priorMapFromCloud(const std::filesystem::path& file);

// A dataset's scans at `poses` (one per scan), merged.
PriorMap priorMapFromDataset(io::Dataset dataset, std::vector<Pose> poses, std::string name);

struct MapRun {
  closure::MapAlignment alignment;  // the session's frame in the map's point coordinates
  nlohmann::json alignment_report;  // its search (alignmentReport), for report.json
  std::vector<Pose> placed;         // the input poses placed so, before the method
  // The method's result (hierarchy without its own refinement, then refined
  // against the map), poses in the map's point coordinates (inMapFrame
  // turns them into the map's frame).
  pipeline::HbaResult result;
  std::size_t map_points_near = 0;  // of the map, near the session: what it was refined against
  double plane_rms_before_m = 0.0;
  double plane_rms_after_m = 0.0;
};

// Places the session (`scans` at `poses`, called `session_name`) in `map`,
// runs the method on it there, and refines it against the map. Throws
// hba::Error, naming the session and the map, when it cannot be placed.
MapRun runInMap(const PriorMap& map, const io::ScanSource& scans, const std::vector<Pose>& poses,
                const HbaSettings& settings, const pipeline::ClosureInputs& closures,
                const std::string& session_name);

// Poses in the map's point coordinates moved into the map's own frame.
std::vector<Pose> inMapFrame(const PriorMap& map, const std::vector<Pose>& poses);

// report.json's "map": the placement and the refinement against the map.
nlohmann::json mapReport(const PriorMap& map, const MapRun& run);

}  // namespace hba::pipeline
