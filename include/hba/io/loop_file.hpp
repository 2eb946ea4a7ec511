#pragma once
// Loop-closure pairs from a text file (docs/closure.md): one pair a line,
//   i j                          frames i and j see the same place
//   i j tx ty tz qx qy qz qw     ... and T_i^-1 * T_j, the pose of j seen from i
// as place recognition (ScanContext and the like) writes them. Frame indices
// count from 0 in the order hba reads the scans. '#' starts a comment line.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include "hba/core/pose.hpp"

namespace hba::io {

struct LoopRecord {
  std::size_t from = 0;
  std::size_t to = 0;
  std::optional<Pose> relative;  // T_from^-1 * T_to, when the file gives it
  std::size_t line = 0;          // 1-based, for messages
};

// Throws hba::Error naming the file and line: a missing or empty file, a line
// of another length, an index that is not a whole number or not below
// `frame_count`, a pair of one frame with itself, a degenerate quaternion.
std::vector<LoopRecord> readLoopFile(const std::filesystem::path& path, std::size_t frame_count);

}  // namespace hba::io
