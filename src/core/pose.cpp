#include "hba/core/pose.hpp"

#include <algorithm>
#include <cmath>

#include "hba/core/lie.hpp"

namespace hba {

Pose::Pose(const Quat& rotation, const Vec3& translation) : q(rotation.normalized()), t(translation) {}

Pose::Pose(const Mat3& rotation, const Vec3& translation) : q(Quat(rotation).normalized()), t(translation) {}

Pose Pose::fromMatrix(const Mat4& m) {
  return Pose(Mat3(m.topLeftCorner<3, 3>()), Vec3(m.topRightCorner<3, 1>()));
}

Mat4 Pose::matrix() const {
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = R();
  m.topRightCorner<3, 1>() = t;
  return m;
}

Pose Pose::inverse() const {
  const Quat qi = q.conjugate();
  Pose out;
  out.q = qi;
  out.t = -(qi * t);
  return out;
}

Pose Pose::operator*(const Pose& other) const {
  Pose out;
  out.q = (q * other.q).normalized();
  out.t = q * other.t + t;
  return out;
}

Pose relative(const Pose& a, const Pose& b) { return a.inverse() * b; }

Pose interpolate(const Pose& a, const Pose& b, double s) {
  return Pose(a.q.slerp(s, b.q).normalized(), (1.0 - s) * a.t + s * b.t);
}

Pose poseAtTime(const Trajectory& trajectory, double t) {
  const std::vector<double>& stamps = trajectory.stamps;
  const std::size_t n = std::min(stamps.size(), trajectory.poses.size());
  if (n == 0) return Pose::identity();
  if (n == 1) return trajectory.poses.front();
  // The segment [k, k + 1] holding t, or the end segment nearest it.
  const auto after = std::upper_bound(stamps.begin(), stamps.begin() + static_cast<std::ptrdiff_t>(n), t);
  const auto at = static_cast<std::size_t>(after - stamps.begin());
  if (at > 0 && stamps[at - 1] == t) return trajectory.poses[at - 1];  // on a stamp: its pose exactly
  const std::size_t k = std::clamp<std::size_t>(at, 1, n - 1) - 1;
  const double length = stamps[k + 1] - stamps[k];
  if (!(length > 0.0)) return trajectory.poses[k];
  const double s = std::clamp((t - stamps[k]) / length, -1.0, 2.0);
  return interpolate(trajectory.poses[k], trajectory.poses[k + 1], s);
}

Trajectory spreadCorrections(const Trajectory& before, const std::vector<Pose>& after,
                             const Trajectory& dense) {
  Trajectory corrections;
  corrections.stamps = before.stamps;
  for (std::size_t k = 0; k < after.size() && k < before.size(); ++k) {
    corrections.poses.push_back(after[k] * before.poses[k].inverse());
  }
  corrections.stamps.resize(corrections.poses.size());
  Trajectory out;
  out.stamps = dense.stamps;
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const double t = dense.stamps.at(i);
    // Held, not extrapolated, beyond the first and last keyframes.
    const double inside =
        corrections.stamps.empty() ? t : std::clamp(t, corrections.stamps.front(), corrections.stamps.back());
    out.poses.push_back(poseAtTime(corrections, inside) * dense.poses[i]);
  }
  return out;
}

std::vector<Pose> translated(const std::vector<Pose>& poses, const Vec3& offset) {
  std::vector<Pose> out = poses;
  for (Pose& pose : out) pose.t += offset;
  return out;
}

double pathLength(const std::vector<Pose>& poses) {
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) length += (poses[i].t - poses[i - 1].t).norm();
  return length;
}

PoseChange largestChange(const std::vector<Pose>& before, const std::vector<Pose>& after) {
  PoseChange change;
  for (std::size_t i = 0; i < before.size() && i < after.size(); ++i) {
    change.translation_m = std::max(change.translation_m, (after[i].t - before[i].t).norm());
    change.rotation_deg = std::max(change.rotation_deg,
                                   so3Log(Quat(before[i].q.conjugate() * after[i].q)).norm() * 180.0 / M_PI);
  }
  return change;
}

}  // namespace hba
