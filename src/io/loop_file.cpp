#include "hba/io/loop_file.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "hba/core/error.hpp"
#include "pose_file_lines.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

[[noreturn]] void failAtLine(const fs::path& path, std::size_t line, const std::string& problem) {
  failAt(path, "line " + std::to_string(line) + ": " + problem);
}

std::size_t frameIndex(const fs::path& path, std::size_t line, double value, std::size_t frame_count,
                       const char* which) {
  if (!(value >= 0.0) || value != std::floor(value)) {
    failAtLine(path, line, std::string(which) + " frame must be a whole number >= 0");
  }
  if (value >= static_cast<double>(frame_count)) {
    // As written: a whole number, perhaps beyond any integer type (2e+33).
    std::ostringstream number;
    number << std::setprecision(15) << value;
    failAtLine(path, line,
               std::string(which) + " frame " + number.str() + " is beyond the sequence (" +
                   std::to_string(frame_count) + " frames, counted from 0)");
  }
  return static_cast<std::size_t>(value);
}

}  // namespace

std::vector<LoopRecord> readLoopFile(const fs::path& path, std::size_t frame_count) {
  std::vector<LoopRecord> loops;
  for (const detail::NumberRow& row : detail::readNumberRows(path)) {
    const std::vector<double>& v = row.values;
    if (v.size() != 2 && v.size() != 9) {
      failAtLine(
          path, row.line,
          "expected 2 numbers (i j) or 9 (i j tx ty tz qx qy qz qw), found " + std::to_string(v.size()));
    }
    LoopRecord loop;
    loop.line = row.line;
    loop.from = frameIndex(path, row.line, v[0], frame_count, "first");
    loop.to = frameIndex(path, row.line, v[1], frame_count, "second");
    if (loop.from == loop.to) failAtLine(path, row.line, "a frame cannot close a loop with itself");
    if (v.size() == 9) {
      // The TUM order of the pose file reader: tx ty tz qx qy qz qw.
      detail::NumberRow tum{row.line, {0.0, v[2], v[3], v[4], v[5], v[6], v[7], v[8]}};
      loop.relative = detail::poseFromRow(path, tum, PoseFormat::Tum);
    }
    loops.push_back(loop);
  }
  return loops;
}

}  // namespace hba::io
