#pragma once
// Position priors from a text file (docs/closure.md): GNSS or surveyed
// positions of the sensor in a local metric frame (ENU, UTM: metres), timed
// on the scans' clock. One a line,
//   t x y z sigma                 one standard deviation (m) for every axis
//   t x y z sigma_x sigma_y sigma_z
// stamps in seconds and increasing; '#' starts a comment line.
#include <cstddef>
#include <filesystem>
#include <vector>

#include "hba/core/types.hpp"

namespace hba::io {

struct TimedPosition {
  double stamp = 0.0;  // s
  Vec3 position = Vec3::Zero();
  Vec3 sigma = Vec3::Ones();  // m, per axis
  std::size_t line = 0;       // 1-based, for messages
};

// Throws hba::Error naming the file and line: a missing or empty file, a line
// of another length, a sigma that is not positive, stamps that do not
// increase.
std::vector<TimedPosition> readPositionPriorFile(const std::filesystem::path& path);

}  // namespace hba::io
