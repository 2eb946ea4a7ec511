#include "recording_entry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/error.hpp"
#include "hba/io/deskew.hpp"

namespace hba::cli {
namespace {

// A text of the entry, or "" when it has none; anything else than text is refused.
std::string entryText(const nlohmann::json& entry, const char* key,
                      const std::filesystem::path& report_file) {
  const auto found = entry.find(key);
  if (found == entry.end() || found->is_null()) return "";
  if (!found->is_string()) failAt(report_file, std::string("input.recording.") + key + " is not text");
  return found->get<std::string>();
}

// A number of the entry within [low, high], or 0 when it has none.
double entryNumber(const nlohmann::json& entry, const char* key, double low, double high,
                   const std::filesystem::path& report_file) {
  const auto found = entry.find(key);
  if (found == entry.end() || found->is_null()) return 0.0;
  const double value = found->is_number() ? found->get<double>() : std::nan("");
  if (!(value >= low && value <= high)) {
    failAt(report_file, fmt::format("input.recording.{} is not a number from {:g} to {:g}", key, low, high));
  }
  return value;
}

}  // namespace

nlohmann::json recordingEntry(const rec::Recording& recording, const DatasetArgs& data) {
  return {{"format", recording.format()},
          {"cloud_topic", recording.cloudTopic()},
          // A trajectory from a file (--poses) is input.poses; the topic otherwise.
          {"pose_topic", data.poses.empty() ? recording.poseTopic() : std::string()},
          {"tf_frames", data.tf_frames},
          {"time_offset", recording.timeOffset()},
          {"keyframe_distance", data.recording.keyframe_distance},
          {"keyframe_angle", data.recording.keyframe_angle},
          {"deskew", data.deskew}};
}

void applyRecordingEntry(const nlohmann::json& entry, const std::filesystem::path& report_file,
                         DatasetArgs& data) {
  if (!entry.is_object())
    failAt(report_file, "input.recording is not an object (not written by hba optimize?)");
  rec::RecordingOptions& options = data.recording;
  const auto fill = [](std::string& flag, const std::string& value) {
    if (flag.empty()) flag = value;
  };
  fill(options.cloud_topic, entryText(entry, "cloud_topic", report_file));
  fill(options.pose_topic, entryText(entry, "pose_topic", report_file));
  fill(data.tf_frames, entryText(entry, "tf_frames", report_file));
  if (options.time_offset == 0.0)
    options.time_offset = entryNumber(entry, "time_offset", -1e6, 1e6, report_file);
  if (options.keepsEveryScan()) {
    options.keyframe_distance = entryNumber(entry, "keyframe_distance", 0.0, 1000.0, report_file);
    options.keyframe_angle = entryNumber(entry, "keyframe_angle", 0.0, 180.0, report_file);
  }
  const std::string deskew = entryText(entry, "deskew", report_file);
  if (!deskew.empty()) {
    const std::vector<std::string> names = enumNames<io::DeskewMode>();
    if (std::find(names.begin(), names.end(), deskew) == names.end())
      failAt(report_file, "input.recording.deskew is '" + deskew + "', not a --deskew choice");
    if (data.deskew == "auto") data.deskew = deskew;  // "auto" is the flag's default
  }
}

}  // namespace hba::cli
