// Files that sit beside the trajectory: KITTI's calib.txt and times.txt.
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include "core/input_file.hpp"
#include "dataset_parts.hpp"
#include "hba/core/error.hpp"
#include "pose_file_lines.hpp"

namespace hba::io::detail {
namespace fs = std::filesystem;

namespace {

// Splits "Tr: 1 2 3 ..." at whitespace after the key and parses the numbers.
NumberRow parseCalibValues(const fs::path& path, std::size_t line, std::string_view text) {
  NumberRow row{line, {}};
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    std::size_t end = pos;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    if (end == pos) break;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data() + pos, text.data() + end, value);
    if (ec != std::errc() || ptr != text.data() + end || !std::isfinite(value)) {
      failAt(path, "line " + std::to_string(line) + ": '" + std::string(text.substr(pos, end - pos)) +
                       "' is not a finite number");
    }
    row.values.push_back(value);
    pos = end;
  }
  return row;
}

}  // namespace

std::optional<Pose> readKittiLidarToCamera(const fs::path& calib_file) {
  std::istringstream in(readTextFile(calib_file));
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    // KITTI odometry names it "Tr:", the object benchmark "Tr_velo_to_cam:".
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = text.substr(0, colon);
    if (key != "Tr" && key != "Tr_velo_to_cam") continue;
    const NumberRow row = parseCalibValues(calib_file, line, std::string_view(text).substr(colon + 1));
    if (row.values.size() != 12) {
      failAt(calib_file, "line " + std::to_string(line) + ": " + key +
                             " needs 12 numbers (row-major 3x4), found " + std::to_string(row.values.size()));
    }
    return poseFromRow(calib_file, row, PoseFormat::Kitti);
  }
  return std::nullopt;
}

}  // namespace hba::io::detail
