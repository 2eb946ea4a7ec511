#pragma once
// How well the shared planes hold each direction of a relative pose: the
// Fisher information of the `to` end (the `from` end held), inverted, and its
// translation and rotation parts read out. A corridor or a flat field leaves
// a direction free or nearly so, which a loop factor must not pretend to know.
#include "hba/core/types.hpp"

namespace hba::closure {

struct HeldDirections {
  double sigma_m = 0.0;    // standard deviation of the least held translation direction
  double sigma_deg = 0.0;  // and rotation direction
  // Least held over best held standard deviation, within translation and within rotation.
  double translation_ratio = 0.0;
  double rotation_ratio = 0.0;
  Vec3 weakest_translation = Vec3::UnitX();  // unit, in the `from` frame
  Vec3 weakest_rotation = Vec3::UnitZ();     // unit axis
};

// `fisher` in the BA's (dt, dphi) coordinates of the `to` end. A direction
// with no information gets infinite sigmas and ratios.
HeldDirections heldDirections(const Mat6& fisher);

}  // namespace hba::closure
