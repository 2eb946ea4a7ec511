#pragma once
// Gently rolling ground: a smooth, seeded height field z = h(x, y) made of a
// few long sinusoids (wavelengths of hundreds of metres, slopes of a few
// percent), like the grades of an ordinary town.
#include <array>
#include <cstdint>

#include "hba/core/types.hpp"

namespace hba::sim {

class Terrain {
 public:
  // max_slope: the steepest grade the field can reach (0.03 = 3 %); 0 = flat.
  Terrain(std::uint64_t seed, double max_slope);

  double height(double x, double y) const;
  // (dh/dx, dh/dy).
  Eigen::Vector2d gradient(double x, double y) const;
  double maxSlope() const { return max_slope_; }

 private:
  struct Wave {
    Eigen::Vector2d wave_vector;  // direction * 2 pi / wavelength
    double amplitude = 0.0;
    double phase = 0.0;
  };
  std::array<Wave, 3> waves_;
  double max_slope_ = 0.0;
};

}  // namespace hba::sim
