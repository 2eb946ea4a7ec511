#pragma once
// Private to the io module: the steps of Dataset::open, one file each.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/io/dataset.hpp"

namespace hba::io::detail {

using Notes = std::vector<DatasetNote>;

// --- dataset_scans.cpp: the scan files of one folder ---

// True if `dir` holds at least one scan file (stops at the first).
bool containsScanFile(const std::filesystem::path& dir);
struct ScanFiles {
  std::vector<std::filesystem::path> paths;
  std::vector<double> stamps;  // seconds, when every name is a time; else empty
};
// The scan files of `dir`. Names that are all times (1577836980.099104600.pcd,
// or Unix ms / µs / ns: 13, 16, 17-19 digits) are ordered by time and give stamps;
// otherwise by the number in their names (the last run of digits: 7.pcd,
// 000007.pcd, scan_7.pcd). Throws hba::Error naming the files for: no scans,
// mixed extensions, a name without a number, two files with one number or
// time, or a gap in the numbering.
ScanFiles listScans(const std::filesystem::path& dir);
// What `dir` holds, for a message where scans were expected: "14 .vtk files
// (000000.vtk ... 000013.vtk)", "2 folders", "nothing". Hidden files left out.
std::string folderContents(const std::filesystem::path& dir);

// --- dataset_time_match.cpp: scans named by time, poses stamped ---

struct TimeMatch {
  std::vector<std::size_t> pose_of_scan;  // for each kept scan, its pose
  std::vector<std::size_t> kept_scans;    // scans that have a pose, ascending
};
// Pairs every scan with the pose nearest in time, within half the median
// interval between scans; of two scans nearest to one pose, the closer keeps
// it. Scans without a pose are left out (with a warning); more than half left
// out is an error naming `scans_dir` and `poses_file`. The stamps must
// increase (the caller checks the scans').
TimeMatch matchByTime(const std::vector<double>& scan_stamps, const std::vector<double>& pose_stamps,
                      const std::filesystem::path& scans_dir, const std::filesystem::path& poses_file,
                      Notes& notes);

// --- dataset_discovery.cpp: which folder and which trajectory ---

// The folder of scans under `root` (pcd/, Scans/, velodyne/, ... or root
// itself). Throws hba::Error if none or several candidates hold scans.
std::filesystem::path findScansDir(const std::filesystem::path& root, Notes& notes);
// The trajectory file in `root`, by a fixed order of preference (odometry
// before optimized poses). Throws hba::Error if none, or if only unknown
// names remain and several could be it.
std::filesystem::path findTrajectoryFile(const std::filesystem::path& root,
                                         const std::filesystem::path& scans_dir, Notes& notes);
// An override path as the user typed it: absolute, else relative to the
// working folder, else relative to `root`. Throws hba::Error if not found.
std::filesystem::path resolveOverride(const std::filesystem::path& root, const std::filesystem::path& path,
                                      const char* what);

// --- dataset_sidecars.cpp: calib.txt ---

// KITTI calib.txt's `Tr:` line (LiDAR -> camera 0), or nullopt if it has none.
std::optional<Pose> readKittiLidarToCamera(const std::filesystem::path& calib_file);

}  // namespace hba::io::detail
