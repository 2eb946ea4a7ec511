#pragma once
// The parts of `hba optimize` shared by one sequence and several sessions:
// its arguments, settings, input checks and outputs.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/staging_folder.hpp"
#include "dataset_args.hpp"
#include "hba/closure/session_alignment.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/closure_files.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "setting_flags.hpp"

namespace hba::cli::optimize {

struct Args {
  DatasetArgs data;
  std::vector<std::string> more_sessions;  // DIR is the first session
  std::string map;                         // a fixed map: a cloud file or an earlier output
  std::string fixed;                       // a fixed map: a dataset at its poses
  std::string align = "register";
  std::string output;
  std::string config;
  SettingFlags settings;
  std::string ground_truth;
  pipeline::ClosureFiles closure_files;  // --loops, --priors, --prior-max-gap
  bool no_render = false;
  bool no_report_page = false;
  bool no_convention_check = false;
  bool no_memory_check = false;
  bool force = false;
  bool print_config = false;
  bool print_plan = false;  // the run's plan as JSON, and stop
  bool every_scan = false;  // a recording's every scan's pose, keyframes or not
  int deskew_passes = 2;    // raw sweeps: runs, each deskewing by the poses the last one found
};

double peakMemoryMiB();
// Says, before any work, what --force will replace at the end.
void announceReplacement(const StagingFolder& staging);
// Defaults, then the YAML file, then the flags given on the command line.
HbaSettings mergeSettings(const Args& args);
// --loops (frame indices of `frames`) and --priors (by `dataset`'s stamps), read before any work.
// With several sessions (`datasets`, the first frame of each at `starts`), each
// prior goes to the session whose scans it falls among in time.
pipeline::ClosureInputs readClosureInputs(const Args& args, const std::vector<const io::Dataset*>& datasets,
                                          const std::vector<std::size_t>& starts, std::size_t frames);
// Refuses input in another convention, naming the flag that fixes it; what it found, for the report.
nlohmann::json checkConventions(const Args& args, const io::ScanSource& source, const io::Dataset& dataset);
// The sensor poses in three formats (and in the input's frame when it was another); the files written.
std::vector<std::string> writeOptimizedPoses(const std::filesystem::path& out, const io::Dataset& dataset,
                                             const std::vector<Pose>& poses);
// every_scan_poses_tum.txt: every scan of a recording with its pose (the
// keyframes' corrections spread to the scans between them); the files written.
std::vector<std::string> writeEveryScanPoses(const std::filesystem::path& out, const io::Dataset& dataset,
                                             const std::vector<Pose>& poses);
// report.json's content for `dataset` (the caller may add to it), and writing it.
// A recording's topics, offset and keyframes (`data`'s flags) go to its
// input.recording, so that hba view OUT and --map OUT read the same scans.
nlohmann::json reportJson(const pipeline::HbaResult& result, const io::Dataset& dataset,
                          const DatasetArgs& data, const HbaSettings& settings,
                          const nlohmann::json& conventions);
// Returns what was written (with the peak memory so far).
nlohmann::json writeReport(const std::filesystem::path& out, const nlohmann::json& report);
// Ground truth for the picture, the page and the windows' errors: --gt, or
// the simulator's gt.txt beside the data; none when it has not `frames`
// poses (a warning).
// Read before any work: a bad file must not cost a finished run.
std::optional<Trajectory> readGroundTruth(const Args& args, const io::Dataset& dataset, std::size_t frames);
// report.json's window_errors: every pyramid window of `result` against
// `gt` (pipeline/window_errors.hpp), also logged as a table.
nlohmann::json windowErrorsReport(const pipeline::HbaResult& result, const std::vector<Pose>& input,
                                  const Trajectory& gt);
// before_after.png of `before` and `result.poses` (with `gt` when given).
// The scans are read as the optimization kept them (parsed and downsampled
// once, at `scan_voxel`) when it kept them at least as fine as the picture's
// voxel; from `scans` otherwise. False, with a warning, when the picture
// would not fit in the memory available: left out.
bool writePicture(const io::ScanSource& scans, const pipeline::HbaResult& result, double scan_voxel,
                  const std::vector<Pose>& before, const std::optional<Trajectory>& gt,
                  const std::filesystem::path& out);
// report.html (docs/report_page.md): the map in 3D with the input and the
// optimized poses, the run's `report` and the picture in `out`, if drawn. The
// scans are read as for the picture. False, with a warning, when it would
// not fit in the memory available: left out.
bool writeReportPage(const io::ScanSource& scans, const pipeline::HbaResult& result, double scan_voxel,
                     const std::vector<Pose>& before, const std::optional<Trajectory>& gt,
                     const nlohmann::json& report, const std::string& title,
                     const std::filesystem::path& out);

// Several sessions (args.more_sessions): optimize_sessions.cpp.
void runSessions(const Args& args, HbaSettings settings);
// A new session against a map that stays put (--map, --fixed): optimize_map.cpp.
void runWithMap(const Args& args, HbaSettings settings);

}  // namespace hba::cli::optimize
