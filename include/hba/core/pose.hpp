#pragma once
// A rigid pose T = (R, t) that maps sensor points into the world: p_w = R p + t.
#include <vector>

#include "hba/core/types.hpp"

namespace hba {

struct Pose {
  Quat q = Quat::Identity();  // unit quaternion, rotation sensor -> world
  Vec3 t = Vec3::Zero();      // sensor origin in the world

  Pose() = default;
  Pose(const Quat& rotation, const Vec3& translation);
  Pose(const Mat3& rotation, const Vec3& translation);
  static Pose identity() { return Pose(); }
  static Pose fromMatrix(const Mat4& m);

  Mat3 R() const { return q.toRotationMatrix(); }
  Mat4 matrix() const;
  Pose inverse() const;
  Pose operator*(const Pose& other) const;
  Vec3 operator*(const Vec3& p) const { return q * p + t; }
};

// Relative pose a^-1 * b: b expressed in the frame of a.
Pose relative(const Pose& a, const Pose& b);

// The pose a share s of the way from a to b (0: a, 1: b): the position
// linearly, the orientation along the shortest arc (slerp).
Pose interpolate(const Pose& a, const Pose& b, double s);

// A sequence of poses with optional timestamps (empty, or one per pose).
struct Trajectory {
  std::vector<Pose> poses;
  std::vector<double> stamps;

  std::size_t size() const { return poses.size(); }
  bool empty() const { return poses.empty(); }
  bool hasStamps() const { return !stamps.empty(); }
};

// The pose at time t of a stamped trajectory (stamps increasing): on a
// stamp its pose exactly; between two poses interpolated; beyond an end
// extrapolated by the end segment's motion, at most one segment's length
// of time, then held.
Pose poseAtTime(const Trajectory& trajectory, double t);

// Every pose of `dense` (stamped, e.g. every scan of a recording) moved as
// the keyframes around it were: keyframe k's correction C_k = after_k *
// before_k^-1 (`before`: the keyframes as they were, stamped), interpolated
// by time between the two keyframes around each stamp and held beyond the
// ends, applied as C * dense_i. The dense poses keep their own motion
// between keyframes. Both sets share one frame; `after` has one pose per
// keyframe.
Trajectory spreadCorrections(const Trajectory& before, const std::vector<Pose>& after,
                             const Trajectory& dense);

// The poses moved by `offset` (added to every translation).
std::vector<Pose> translated(const std::vector<Pose>& poses, const Vec3& offset);

// Sum of distances between consecutive positions, in metres.
double pathLength(const std::vector<Pose>& poses);

// The largest change of any pose between two equally long sequences: of
// its position (m) and of its orientation (deg), each over all poses.
struct PoseChange {
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};
PoseChange largestChange(const std::vector<Pose>& before, const std::vector<Pose>& after);

}  // namespace hba
