#pragma once
// report.json's input.recording: what a run of a recording read (its topics,
// time offset, keyframes, deskewing), written by hba optimize and read back
// by `hba view OUT` and `--map OUT`, so that they read the same scans: a
// keyframed run's pose.json has one pose per keyframe, not per cloud.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "dataset_args.hpp"
#include "hba/rec/recording.hpp"

namespace hba::cli {

// The entry for `recording`, opened with `data`'s flags.
nlohmann::json recordingEntry(const rec::Recording& recording, const DatasetArgs& data);

// Sets in `data` what `entry` gives, except where `data` has a flag of its
// own (given on the command line). Throws hba::Error naming `report_file`
// for an entry that is not as hba writes it.
void applyRecordingEntry(const nlohmann::json& entry, const std::filesystem::path& report_file,
                         DatasetArgs& data);

}  // namespace hba::cli
