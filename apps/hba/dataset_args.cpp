#include "dataset_args.hpp"

namespace hba::cli {

void DatasetArgs::addTo(CLI::App* command) {
  command->add_option("DIR", dir, "Dataset folder (HBA, scans+trajectory, or KITTI layout)")
      ->required();
  command->add_option("--scans", scans, "Folder of scans (overrides detection)");
  command->add_option("--poses", poses, "Trajectory file (overrides detection)");
  command->add_option("--format", format, "Format of the --poses file")
      ->check(CLI::IsMember({"kitti", "tum", "hba"}));
}

io::Dataset DatasetArgs::open() const {
  io::DatasetOverrides overrides;
  if (!scans.empty()) overrides.scans_dir = scans;
  if (!poses.empty()) overrides.poses_file = poses;
  if (!format.empty()) overrides.pose_format = io::poseFormatFromString(format);
  return io::Dataset::open(dir, overrides);
}

}  // namespace hba::cli
