// Finds the scans folder and the trajectory file of a dataset folder by fixed
// orders of preference, so the same folder always opens the same way.
#include <algorithm>
#include <array>
#include <cctype>
#include <string>
#include <system_error>

#include "core/input_file.hpp"
#include "dataset_parts.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_formats.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

// pcd/ first: the original HBA layout.
constexpr std::array<const char*, 9> kScanFolderNames = {"pcd",  "Scans", "scans",       "velodyne", "clouds",
                                                         "pcds", "PCD",   "pointclouds", "frames"};

// Odometry first (the drifting input HBA is meant to refine), loop-closed or
// optimized trajectories last.
constexpr std::array<const char*, 10> kTrajectoryNames = {
    "odom_poses.txt", "pose.json",    "poses.txt",       "poses.json",    "traj.txt",
    "trajectory.txt", "odometry.txt", "poses_kitti.txt", "poses_tum.txt", "optimized_poses.txt"};

// Text files that sit beside trajectories but are not one.
constexpr std::array<const char*, 5> kNotTrajectories = {"calib.txt", "times.txt", "timestamps.txt",
                                                         "readme.txt", "README.txt"};

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

template <std::size_t N>
std::vector<std::string> asStrings(const std::array<const char*, N>& names) {
  return std::vector<std::string>(names.begin(), names.end());
}

// A folder under one of the usual names; a link loop there is an error, not
// "no scans found".
bool isFolder(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (status.type() == fs::file_type::none) requireFolder(dir, "scans folder");  // says why
  return fs::is_directory(status);
}

// Something is at `path`, even a broken link or a loop (its reader says what).
bool anythingAt(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type() != fs::file_type::not_found;
}

// KITTI odometry keeps poses as <sequence>.txt (00.txt ... 21.txt).
bool looksLikeKittiSequenceFile(const fs::path& path) {
  const std::string stem = path.stem().string();
  return path.extension() == ".txt" && stem.size() == 2 && std::isdigit(stem[0]) && std::isdigit(stem[1]);
}

// Files of unknown name that might be a trajectory: *.txt, *.json, *.tum.
std::vector<fs::path> unknownTrajectoryCandidates(const fs::path& root) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(root, ec)) {
    const fs::path& path = entry.path();
    const std::string name = path.filename().string();
    const std::string ext = path.extension().string();
    if (name.front() == '.' || !entry.is_regular_file(ec)) continue;
    if (ext != ".txt" && ext != ".json" && ext != ".tum") continue;
    if (std::find(kNotTrajectories.begin(), kNotTrajectories.end(), name) != kNotTrajectories.end()) continue;
    found.push_back(path);
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<std::string> fileNames(const std::vector<fs::path>& paths) {
  std::vector<std::string> names;
  for (const fs::path& path : paths) names.push_back(path.filename().string());
  return names;
}

}  // namespace

fs::path findScansDir(const fs::path& root, Notes& notes) {
  std::vector<fs::path> candidates;
  for (const char* name : kScanFolderNames) {
    const fs::path dir = root / name;
    if (isFolder(dir) && containsScanFile(dir)) candidates.push_back(dir);
  }
  if (candidates.size() > 1) {
    failAt(root,
           "several folders hold scans (" + joined(fileNames(candidates)) + "); choose one with --scans");
  }
  if (candidates.size() == 1) return candidates.front();
  if (containsScanFile(root)) {
    notes.push_back(
        {DatasetNote::Level::Info, "no scans subfolder; using the scans in " + root.string() + " itself"});
    return root;
  }
  // What stands where scans were looked for: a folder of .vtk scans is named as such.
  std::string found = "the folder itself holds " + folderContents(root);
  for (const char* name : kScanFolderNames) {
    if (isFolder(root / name)) found += "; " + std::string(name) + "/ holds " + folderContents(root / name);
  }
  failAt(root, "no scans found: none of the folders " + joined(asStrings(kScanFolderNames)) +
                   " exists with " + scanFormatList() +
                   " files in it, nor are there scans in the folder "
                   "itself (" +
                   found + "); give the folder with --scans");
}

fs::path findTrajectoryFile(const fs::path& root, const fs::path& scans_dir, Notes& notes) {
  std::vector<fs::path> known;
  for (const char* name : kTrajectoryNames) {
    // A FIFO or a loop under a trajectory's name is an error, not passed over.
    if (regularFileIsPresent(root / name)) known.push_back(root / name);
  }
  // The original HBA layout pairs pcd/ with pose.json: prefer it there.
  const auto hba_pose = std::find(known.begin(), known.end(), root / "pose.json");
  if (scans_dir.filename() == "pcd" && hba_pose != known.end())
    std::rotate(known.begin(), hba_pose, hba_pose + 1);
  // KITTI odometry: <sequence>.txt beside velodyne/ (e.g. 00/00.txt).
  if (known.empty()) {
    for (const fs::path& path : unknownTrajectoryCandidates(root)) {
      if (looksLikeKittiSequenceFile(path)) known.push_back(path);
    }
    if (known.size() > 1) {
      failAt(root,
             "several KITTI sequence pose files (" + joined(fileNames(known)) + "); choose one with --poses");
    }
  }
  if (!known.empty()) {
    if (known.size() > 1) {
      std::vector<fs::path> others(known.begin() + 1, known.end());
      notes.push_back({DatasetNote::Level::Info, "using " + known.front().filename().string() +
                                                     "; also found " + joined(fileNames(others)) +
                                                     " (pick one with --poses)"});
    }
    return known.front();
  }
  const std::vector<fs::path> unknown = unknownTrajectoryCandidates(root);
  if (unknown.size() == 1) {
    notes.push_back({DatasetNote::Level::Info,
                     "no trajectory file with a usual name; trying " + unknown.front().string()});
    return unknown.front();
  }
  if (unknown.size() > 1) {
    failAt(root, "cannot tell which file is the trajectory (" + joined(fileNames(unknown)) +
                     "); choose one with --poses");
  }
  failAt(root, "no trajectory file found (looked for " + joined(asStrings(kTrajectoryNames)) +
                   "); give one with --poses");
}

fs::path resolveOverride(const fs::path& root, const fs::path& path, const char* what) {
  if (path.is_absolute() || anythingAt(path)) {
    if (!anythingAt(path)) failAt(path, std::string(what) + " not found");
    return path;
  }
  if (anythingAt(root / path)) return root / path;
  failAt(path, std::string(what) + " not found (looked in the working folder and in " + root.string() + ")");
}

}  // namespace hba::io::detail
