#pragma once
// The dataset arguments shared by every command that reads a sequence:
// DIR (or a recording) plus the overrides --scans, --poses, --format,
// --times, the convention flags --invert-poses, --extrinsic, --calib,
// --scans-in-world, and a recording's --cloud-topic, --pose-topic,
// --time-offset, keyframes, and --deskew for raw sweeps.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "hba/io/dataset.hpp"

namespace hba::cli {

struct DatasetArgs {
  std::string dir;
  std::string scans;
  std::string poses;
  std::string format;
  std::string times;
  bool invert_poses = false;
  std::string extrinsic;
  std::string calibration;
  bool scans_in_world = false;
  rec::RecordingOptions recording;
  std::string deskew = "auto";
  std::string tf_frames;  // PARENT:CHILD of a /tf trajectory

  // Adds the positional DIR and the override flags to `command`.
  void addTo(CLI::App* command);
  // Discovers the dataset (overrides win). Throws hba::Error.
  io::Dataset open() const;
};

// The poses of a file that must hold one per scan of `dataset` (a
// trajectory to compare, ground truth). Throws hba::Error naming the file.
std::vector<Pose> readPosesFor(const io::Dataset& dataset, const std::filesystem::path& path);

// A folder's own name ("hku1" for "data/hku1/"), to title a page with.
std::string folderName(const std::filesystem::path& folder);

// "tx ty tz qx qy qz qw" or 12 numbers "r00 r01 r02 tx r10 ... tz" (spaces or
// commas). Throws hba::Error naming `flag` if malformed or not a rotation.
Pose parsePoseArgument(const std::string& text, const std::string& flag);

}  // namespace hba::cli
