#pragma once
// A signature of a place that does not change when the sensor turns about z:
// per ring of distance around the centre, how high the structure stands on
// average over the sectors of the ring (the max height in each ring-sector
// cell, as ScanContext describes a place, then averaged round the ring).
#include <vector>

#include "hba/core/point_cloud.hpp"

namespace hba::closure {

struct PlaceSignature {
  std::vector<double> rings;
};

PlaceSignature placeSignature(const PointCloud& local_map);
// Unit-free distance between two signatures (0: alike).
double signatureDistance(const PlaceSignature& a, const PlaceSignature& b);

}  // namespace hba::closure
