#pragma once
// Aligning one trajectory onto another before comparing them.
//
// The estimate is expressed in its own world frame (its first pose, the
// odometry's start, ...); the ground truth in another. Alignment finds the
// rigid (SE(3)) or similarity (Sim(3)) transform S that best maps estimated
// positions onto ground-truth positions in the least-squares sense
// (Umeyama 1991), exactly as `evo` does with --align / --correct_scale.
#include <string>
#include <vector>

#include "hba/core/enum_names.hpp"
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba::eval {

enum class Alignment { None, SE3, Sim3 };

// x -> scale * R x + t. The identity by default.
struct Similarity {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  double scale = 1.0;

  Vec3 apply(const Vec3& p) const { return scale * (R * p) + t; }
  // A pose moved by S: rotation R * R_pose, position S(t_pose).
  Pose apply(const Pose& pose) const;
};

// argmin over S of sum_i |target_i - S(source_i)|^2, with scale fixed to 1
// unless `with_scale`. Needs at least 3 pairs and non-coincident sources;
// throws hba::Error otherwise. Reflections are excluded (det R = +1).
Similarity umeyama(const std::vector<Vec3>& source, const std::vector<Vec3>& target, bool with_scale);

// The alignment of `estimate` onto `reference` (positions only) of the given
// kind; identity for Alignment::None.
Similarity alignTrajectory(const std::vector<Pose>& reference, const std::vector<Pose>& estimate,
                           Alignment alignment);

}  // namespace hba::eval

namespace hba {
template <>
struct EnumNames<eval::Alignment> {
  static constexpr const char* what = "alignment";
  static constexpr EnumName<eval::Alignment> names[] = {
      {eval::Alignment::None, "none"}, {eval::Alignment::SE3, "se3"}, {eval::Alignment::Sim3, "sim3"}};
};
}  // namespace hba
