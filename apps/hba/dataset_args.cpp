#include "dataset_args.hpp"

#include <spdlog/spdlog.h>

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
  io::Dataset dataset = io::Dataset::open(dir, overrides);
  // Say what discovery chose and noticed, so a wrong guess is visible before a long run.
  spdlog::debug("dataset {}: layout {}, {} scans in {}, poses {} ({})", dataset.root().string(),
               dataset.layout(), dataset.size(), dataset.scansDir().string(),
               dataset.posesFile().string(), io::toString(dataset.poseFormat()));
  for (const io::DatasetNote& note : dataset.notes()) {
    if (note.level == io::DatasetNote::Level::Warning) {
      spdlog::warn("{}", note.text);
    } else {
      spdlog::info("{}", note.text);
    }
  }
  return dataset;
}

}  // namespace hba::cli
