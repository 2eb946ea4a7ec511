#include "hba/sim/terrain.hpp"

#include <cmath>

#include "sim/random.hpp"

namespace hba::sim {

Terrain::Terrain(std::uint64_t seed, double max_slope) : max_slope_(max_slope) {
  auto rng = makeRng(seed, Stream::Terrain);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  std::uniform_real_distribution<double> wavelength(150.0, 450.0);
  for (Wave& wave : waves_) {
    const double heading = angle(rng);
    const double k = 2.0 * M_PI / wavelength(rng);
    wave.wave_vector = Eigen::Vector2d(std::cos(heading), std::sin(heading)) * k;
    // The slope of one wave peaks at amplitude * k; three waves share the budget.
    wave.amplitude = max_slope / (static_cast<double>(waves_.size()) * k);
    wave.phase = angle(rng);
  }
}

double Terrain::height(double x, double y) const {
  double h = 0.0;
  for (const Wave& wave : waves_) {
    h += wave.amplitude * std::sin(wave.wave_vector.dot(Eigen::Vector2d(x, y)) + wave.phase);
  }
  return h;
}

Eigen::Vector2d Terrain::gradient(double x, double y) const {
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  for (const Wave& wave : waves_) {
    g += wave.amplitude * std::cos(wave.wave_vector.dot(Eigen::Vector2d(x, y)) + wave.phase) *
         wave.wave_vector;
  }
  return g;
}

}  // namespace hba::sim
