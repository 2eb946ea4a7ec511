#include "place_signature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hba::closure {
namespace {

constexpr int kRings = 20;
constexpr double kRingWidth = 2.0;  // m: 40 m around the place
constexpr int kSectors = 60;

}  // namespace

PlaceSignature placeSignature(const PointCloud& local_map) {
  const double lowest = -std::numeric_limits<double>::infinity();
  std::vector<double> top(kRings * kSectors, lowest), bottom(kRings * kSectors, -lowest);
  for (const Vec3f& p : local_map.points) {
    const double r = std::hypot(p.x(), p.y());
    const int ring = static_cast<int>(r / kRingWidth);
    if (ring >= kRings) continue;
    const double angle = std::atan2(p.y(), p.x()) + M_PI;
    const int sector = std::min(kSectors - 1, static_cast<int>(angle / (2.0 * M_PI) * kSectors));
    const int cell = ring * kSectors + sector;
    top[cell] = std::max(top[cell], static_cast<double>(p.z()));
    bottom[cell] = std::min(bottom[cell], static_cast<double>(p.z()));
  }
  PlaceSignature s;
  s.rings.assign(kRings, 0.0);
  for (int ring = 0; ring < kRings; ++ring) {
    double sum = 0.0;
    for (int sector = 0; sector < kSectors; ++sector) {
      const int cell = ring * kSectors + sector;
      // The height the cell's points span: structure, not where the ground lies.
      if (top[cell] > lowest) sum += top[cell] - bottom[cell];
    }
    s.rings[ring] = sum / kSectors;
  }
  return s;
}

double signatureDistance(const PlaceSignature& a, const PlaceSignature& b) {
  double difference = 0.0, size = 0.0;
  for (std::size_t k = 0; k < a.rings.size(); ++k) {
    difference += std::abs(a.rings[k] - b.rings[k]);
    size += a.rings[k] + b.rings[k];
  }
  return size > 0.0 ? difference / size : 1.0;
}

}  // namespace hba::closure
