#pragma once
// Sums of points taken relative to the first one: the offsets' sum and the
// sum of their outer products, in one pass. The points of a voxel lie a few
// metres apart, so these shifted sums lose nothing to cancellation, unlike
// raw sums of coordinates far from the origin.
#include "hba/core/types.hpp"

namespace hba {

class ShiftedMoments {
 public:
  explicit ShiftedMoments(const Vec3& origin) : origin_(origin) {}

  void add(const Vec3& p) {
    const Vec3 d = p - origin_;
    sum_ += d;
    xx_ += d.x() * d.x();
    xy_ += d.x() * d.y();
    xz_ += d.x() * d.z();
    yy_ += d.y() * d.y();
    yz_ += d.y() * d.z();
    zz_ += d.z() * d.z();
  }

  const Vec3& origin() const { return origin_; }
  // Sum of the offsets p - origin.
  const Vec3& offsetSum() const { return sum_; }
  // Sum of (p - origin)(p - origin)^T, exactly symmetric.
  Mat3 outerSum() const {
    Mat3 m;
    m << xx_, xy_, xz_, xy_, yy_, yz_, xz_, yz_, zz_;
    return m;
  }

 private:
  Vec3 origin_;
  Vec3 sum_ = Vec3::Zero();
  double xx_ = 0.0, xy_ = 0.0, xz_ = 0.0, yy_ = 0.0, yz_ = 0.0, zz_ = 0.0;
};

}  // namespace hba
