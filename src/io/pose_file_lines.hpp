#pragma once
// Private to the io module: splits a trajectory file into numbered rows of
// numbers, so every reader reports problems as "<file>: line N: ...".
#include <cstddef>
#include <filesystem>
#include <vector>

#include "hba/io/pose_file.hpp"

namespace hba::io::detail {

struct NumberRow {
  std::size_t line = 0;  // 1-based line number in the file
  std::vector<double> values;
};

// Reads every data line of `path`. Skips '#' comment lines and blank lines at
// the end; a blank line between data lines is an error. Throws hba::Error
// naming the file (and line) for a missing or empty file, a token that is not
// a number, or NaN/Inf.
std::vector<NumberRow> readNumberRows(const std::filesystem::path& path);

// Like readNumberRows but parses only up to the first data line (format
// detection; the file is still read whole, trajectories are small).
NumberRow readFirstNumberRow(const std::filesystem::path& path);

// How many numbers one line of `format` has: 7 (hba), 12 (kitti), 8 (tum).
std::size_t numbersPerLine(PoseFormat format);
// The format whose lines have as many numbers as `row`; throws hba::Error
// naming the file and line when no format has that many.
PoseFormat formatOfRow(const std::filesystem::path& path, const NumberRow& row);
// The pose one row of `format` describes (quaternions renormalized, KITTI
// rotations re-orthonormalized). The row must have numbersPerLine(format)
// numbers. Throws hba::Error naming the file and line for a degenerate rotation.
Pose poseFromRow(const std::filesystem::path& path, const NumberRow& row, PoseFormat format);

}  // namespace hba::io::detail
