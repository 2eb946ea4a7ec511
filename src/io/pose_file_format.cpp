// Pose format names and detection from the number count of the first line.
#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "pose_file_lines.hpp"

namespace hba::io {

PoseFormat detectPoseFormat(const std::filesystem::path& path) {
  return detail::formatOfRow(path, detail::readFirstNumberRow(path));
}

namespace detail {

std::size_t numbersPerLine(PoseFormat format) {
  switch (format) {
    case PoseFormat::Hba:
      return 7;
    case PoseFormat::Kitti:
      return 12;
    case PoseFormat::Tum:
      return 8;
  }
  return 0;
}

PoseFormat formatOfRow(const std::filesystem::path& path, const NumberRow& row) {
  for (const PoseFormat format : {PoseFormat::Hba, PoseFormat::Kitti, PoseFormat::Tum}) {
    if (row.values.size() == numbersPerLine(format)) return format;
  }
  failAt(path, "line " + std::to_string(row.line) + ": cannot tell the pose format from " +
                   std::to_string(row.values.size()) +
                   " numbers (expected 7 for hba 'tx ty tz qw qx qy qz', 12 for kitti 3x4 "
                   "[R|t], 8 for tum 't tx ty tz qx qy qz qw')");
}

}  // namespace detail
}  // namespace hba::io
