#include "hba/io/position_prior_file.hpp"

#include <string>

#include "hba/core/error.hpp"
#include "pose_file_lines.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

[[noreturn]] void failAtLine(const fs::path& path, std::size_t line, const std::string& problem) {
  failAt(path, "line " + std::to_string(line) + ": " + problem);
}

}  // namespace

std::vector<TimedPosition> readPositionPriorFile(const fs::path& path) {
  std::vector<TimedPosition> priors;
  for (const detail::NumberRow& row : detail::readNumberRows(path)) {
    const std::vector<double>& v = row.values;
    if (v.size() != 5 && v.size() != 7) {
      failAtLine(path, row.line,
                 "expected 5 numbers (t x y z sigma) or 7 (t x y z sigma_x sigma_y sigma_z), found " +
                     std::to_string(v.size()));
    }
    TimedPosition prior;
    prior.line = row.line;
    prior.stamp = v[0];
    prior.position = Vec3(v[1], v[2], v[3]);
    prior.sigma = v.size() == 5 ? Vec3::Constant(v[4]) : Vec3(v[4], v[5], v[6]);
    if (!(prior.sigma.minCoeff() > 0.0)) {
      failAtLine(path, row.line, "sigma must be positive (metres, one standard deviation)");
    }
    if (!priors.empty() && !(prior.stamp > priors.back().stamp)) {
      failAtLine(
          path, row.line,
          "stamps must increase (this one is not after line " + std::to_string(priors.back().line) + "'s)");
    }
    priors.push_back(prior);
  }
  return priors;
}

}  // namespace hba::io
