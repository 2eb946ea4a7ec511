#pragma once
// Trajectory files.
//  - hba:   the original HBA pose.json, one pose a line: tx ty tz qw qx qy qz
//  - kitti: 12 numbers a line, row-major 3x4 [R | t]
//  - tum:   t tx ty tz qx qy qz qw
// All map sensor points into the world. Quaternions are renormalized on read.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"

namespace hba::io {

enum class PoseFormat { Hba, Kitti, Tum };

// Guesses the format from the first data line's number count (7, 12 or 8).
// Throws hba::Error naming the file if it cannot tell.
PoseFormat detectPoseFormat(const std::filesystem::path& path);

Trajectory readPoses(const std::filesystem::path& path, PoseFormat format);
Trajectory readPoses(const std::filesystem::path& path);  // detected format
// Written atomically, every number in the shortest form that reads back
// exactly. TUM needs stamps; without them the pose index is written as the
// time and the header line says so.
void writePoses(const std::filesystem::path& path, const Trajectory& trajectory, PoseFormat format);

// TUM stamps are seconds, but some exporters write Unix milli-, micro- or
// nanoseconds (1.7e12, 1.7e15, 1.7e18), or nanoseconds from the start (steps
// of 1e8). Such stamps are turned into seconds; returns the unit they were
// in ("ms", "us", "ns"), or "" when they were seconds already.
std::string stampsToSeconds(std::vector<double>& stamps);

// A times.txt: one timestamp (seconds) a line, as KITTI and FAST-LIO write.
std::vector<double> readTimes(const std::filesystem::path& path);
void writeTimes(const std::filesystem::path& path, const std::vector<double>& stamps);

}  // namespace hba::io

namespace hba {
template <>
struct EnumNames<io::PoseFormat> {
  static constexpr const char* what = "pose format";
  static constexpr EnumName<io::PoseFormat> names[] = {
      {io::PoseFormat::Hba, "hba"}, {io::PoseFormat::Kitti, "kitti"}, {io::PoseFormat::Tum, "tum"}};
};
}  // namespace hba
