#include "earlier_output.hpp"

#include <system_error>

#include "core/input_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "pipeline/output_report.hpp"
#include "recording_entry.hpp"

namespace hba::cli {

bool isOptimizeOutput(const std::filesystem::path& folder) {
  return regularFileIsPresent(folder / "report.json") && regularFileIsPresent(folder / "pose.json");
}

nlohmann::json readOutputReport(const std::filesystem::path& folder) {
  if (!isOptimizeOutput(folder))
    failAt(folder, "is not an hba optimize output (no report.json and pose.json)");
  return pipeline::parseOutputReport(readTextFile(folder / "report.json"), folder / "report.json");
}

std::string outputInput(const nlohmann::json& report, const std::filesystem::path& folder, const char* key) {
  return pipeline::reportInputText(report, folder / "report.json", key);
}

bool outputInputFlag(const nlohmann::json& report, const std::filesystem::path& folder, const char* key) {
  return pipeline::reportInputFlag(report, folder / "report.json", key);
}

namespace {
namespace fs = std::filesystem;

// `path` (from report.json's `key`) must be there: a moved dataset is said to
// be one, with where its path came from.
void requirePresent(const std::string& path, const char* key, const fs::path& report_file) {
  if (path.empty()) {
    failAt(report_file, std::string("input.") + key +
                            " is empty: the report does not say what the run read (was it edited?)");
  }
  std::error_code ec;
  if (fs::symlink_status(path, ec).type() == fs::file_type::not_found) {
    failAt(report_file, std::string("names ") + path + " as the run's input." + key +
                            ", which is not there (moved or deleted?): an output's scans are read from the "
                            "dataset the run read; put it back there");
  }
}

}  // namespace

io::Dataset openEarlierDataset(const nlohmann::json& report, const fs::path& folder, DatasetArgs given) {
  const fs::path report_file = folder / "report.json";
  DatasetArgs data = std::move(given);
  data.dir = outputInput(report, folder, "dataset");
  requirePresent(data.dir, "dataset", report_file);
  const std::string poses = outputInput(report, folder, "poses");
  // A recording's own trajectory topic is named as the recording itself.
  if (data.poses.empty() && poses != data.dir) {
    requirePresent(poses, "poses", report_file);
    data.poses = poses;
    if (data.format.empty()) data.format = outputInput(report, folder, "pose_format");
  }
  const nlohmann::json& input = report.at("input");
  if (const auto recording = input.find("recording"); recording != input.end())
    applyRecordingEntry(*recording, report_file, data);
  data.scans_in_world = data.scans_in_world || outputInputFlag(report, folder, "scans_in_world");
  try {
    return data.open();
  } catch (const Error& e) {
    throw Error(report_file.string() + " names the dataset " + data.dir +
                ", which hba cannot read as the run did: " + e.what());
  }
}

std::vector<Pose> earlierPoses(const io::Dataset& dataset, const nlohmann::json& report,
                               const fs::path& folder) {
  const fs::path file = folder / "pose.json";
  std::vector<Pose> poses = io::readPoses(file, io::PoseFormat::Hba).poses;
  if (poses.size() == dataset.size()) return poses;
  const nlohmann::json& input = report.at("input");
  const std::string why =
      dataset.recording() && !input.contains("recording")
          ? ": the run kept keyframes of the recording (or read other topics), and its report.json, "
            "written by an older hba, does not say which; optimize the recording again with this hba to "
            "read the output back"
          : " (was the dataset changed since the run?)";
  failAt(file, std::to_string(poses.size()) + " poses for the " + std::to_string(dataset.size()) +
                   " scans of " + dataset.root().string() + why);
}

}  // namespace hba::cli
