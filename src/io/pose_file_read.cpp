// Reading trajectories: every line becomes a Pose, with its problems reported
// as "<file>: line N: ...".
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"
#include "pose_file_lines.hpp"

namespace hba::io {
namespace fs = std::filesystem;

namespace {

// A quaternion shorter than this is noise, not a rotation to renormalize.
constexpr double kMinQuaternionNorm = 1e-3;
// Singular values of a KITTI rotation further than this from 1 mean the 3x3
// block is not a rotation (printing with 6 digits gives errors near 1e-6).
constexpr double kMaxRotationScaleError = 0.05;

[[noreturn]] void failAtLine(const fs::path& path, std::size_t line, const std::string& problem) {
  failAt(path, "line " + std::to_string(line) + ": " + problem);
}

Quat unitQuaternion(const fs::path& path, std::size_t line, double w, double x, double y, double z) {
  Quat q(w, x, y, z);
  const double norm = q.norm();
  if (norm < kMinQuaternionNorm) {
    failAtLine(path, line, "the quaternion has (near) zero length (" + std::to_string(norm) + ")");
  }
  q.coeffs() /= norm;
  return q;
}

// The rotation nearest to `m` (Frobenius norm), after checking m is close to one.
Mat3 nearestRotation(const fs::path& path, std::size_t line, const Mat3& m) {
  const Eigen::JacobiSVD<Mat3> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3 sigma = svd.singularValues();
  if ((sigma.array() - 1.0).abs().maxCoeff() > kMaxRotationScaleError) {
    failAtLine(path, line,
               "the 3x3 block is not a rotation (singular values " + std::to_string(sigma(0)) + ", " +
                   std::to_string(sigma(1)) + ", " + std::to_string(sigma(2)) + ")");
  }
  const Mat3 r = svd.matrixU() * svd.matrixV().transpose();
  if (r.determinant() < 0.0) failAtLine(path, line, "the 3x3 block is a reflection, not a rotation");
  return r;
}

}  // namespace

Pose detail::poseFromRow(const fs::path& path, const detail::NumberRow& row, PoseFormat format) {
  const std::vector<double>& v = row.values;
  switch (format) {
    case PoseFormat::Hba:  // tx ty tz qw qx qy qz
      return Pose(unitQuaternion(path, row.line, v[3], v[4], v[5], v[6]), Vec3(v[0], v[1], v[2]));
    case PoseFormat::Tum:  // t tx ty tz qx qy qz qw
      return Pose(unitQuaternion(path, row.line, v[7], v[4], v[5], v[6]), Vec3(v[1], v[2], v[3]));
    case PoseFormat::Kitti: {  // r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz
      Mat3 m;
      m << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
      return Pose(nearestRotation(path, row.line, m), Vec3(v[3], v[7], v[11]));
    }
  }
  failAtLine(path, row.line, "unknown pose format");
}

namespace {

std::string describe(PoseFormat format) {
  switch (format) {
    case PoseFormat::Hba:
      return "hba: tx ty tz qw qx qy qz";
    case PoseFormat::Kitti:
      return "kitti: row-major 3x4 [R|t]";
    case PoseFormat::Tum:
      return "tum: t tx ty tz qx qy qz qw";
  }
  return "";
}

Trajectory trajectoryFromRows(const fs::path& path, const std::vector<detail::NumberRow>& rows,
                              PoseFormat format) {
  const std::size_t expected = detail::numbersPerLine(format);
  Trajectory trajectory;
  trajectory.poses.reserve(rows.size());
  if (format == PoseFormat::Tum) trajectory.stamps.reserve(rows.size());
  for (const detail::NumberRow& row : rows) {
    if (row.values.size() != expected) {
      failAtLine(path, row.line,
                 "expected " + std::to_string(expected) + " numbers (" + describe(format) + "), found " +
                     std::to_string(row.values.size()));
    }
    trajectory.poses.push_back(detail::poseFromRow(path, row, format));
    if (format == PoseFormat::Tum) trajectory.stamps.push_back(row.values[0]);
  }
  return trajectory;
}

}  // namespace

Trajectory readPoses(const fs::path& path, PoseFormat format) {
  return trajectoryFromRows(path, detail::readNumberRows(path), format);
}

Trajectory readPoses(const fs::path& path) {
  const std::vector<detail::NumberRow> rows = detail::readNumberRows(path);
  return trajectoryFromRows(path, rows, detail::formatOfRow(path, rows.front()));
}

std::string stampsToSeconds(std::vector<double>& stamps) {
  if (stamps.empty()) return "";
  // Unix time now is 1.7e9 s: its ms, us and ns are three orders apart each.
  const double first = std::abs(stamps.front());
  double scale = first > 1e17 ? 1e-9 : first > 1e14 ? 1e-6 : first > 1e11 ? 1e-3 : 1.0;
  if (scale == 1.0 && stamps.size() > 1) {
    // Stamps from the start of the recording: the median step tells. Above
    // 5e6 they are ns (steps of 5 ms or more), above 5e3 us; seconds never
    // step by hours between scans.
    std::vector<double> steps;
    for (std::size_t i = 1; i < stamps.size(); ++i) steps.push_back(std::abs(stamps[i] - stamps[i - 1]));
    std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2),
                     steps.end());
    const double step = steps[steps.size() / 2];
    scale = step > 5e6 ? 1e-9 : step > 5e3 ? 1e-6 : 1.0;
  }
  if (scale == 1.0) return "";
  for (double& stamp : stamps) stamp *= scale;
  return scale == 1e-9 ? "ns" : scale == 1e-6 ? "us" : "ms";
}

std::vector<double> readTimes(const fs::path& path) {
  std::vector<double> stamps;
  for (const detail::NumberRow& row : detail::readNumberRows(path)) {
    if (row.values.size() != 1) {
      failAt(path, "line " + std::to_string(row.line) + ": expected one timestamp, found " +
                       std::to_string(row.values.size()) + " numbers");
    }
    stamps.push_back(row.values.front());
  }
  return stamps;
}

}  // namespace hba::io
