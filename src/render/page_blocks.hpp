#pragma once
// The report page's binary data (private to render): typed arrays, little
// endian, that the page decodes from base64 into JavaScript's typed arrays.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"
#include "page_points.hpp"

namespace hba::render {

using Bytes = std::vector<std::uint8_t>;

// RFC 4648 base64, with padding, no line breaks.
std::string base64(const Bytes& bytes);
// The same written to `os` piece by piece (no copy of the whole).
void writeBase64(std::ostream& os, const Bytes& bytes);

// The points' scan-frame coordinates as int16 triples, in steps of the
// returned `step` (m): the largest coordinate over 32767.
struct QuantizedPoints {
  Bytes xyz;
  double step = 0.0;
};
QuantizedPoints quantizePoints(const PagePoints& points);

// How many of the points each of `frames` scans holds (uint32 each).
Bytes pointsPerScan(const PagePoints& points, std::size_t frames);

// Intensity as uint8, its 1st to 99th percentile spread over 0-255; none
// when the points have no intensity.
Bytes intensityCodes(const PagePoints& points);

// Poses as float32 rows of 12 (rotation row by row, then position
// relative to `origin`): millimetres 10 km out.
Bytes poseRows(const std::vector<Pose>& poses, const Vec3& origin);

// Where the map got crisper: each point's plane thickness with the `before`
// poses less that with `after` (cells of `cell` m), as uint8: 0 where
// either has no plane, otherwise 128 + the change in steps of
// kChangeStepMm, clamped to 1..255.
inline constexpr double kChangeStepMm = 0.2;
Bytes thicknessChangeCodes(const PagePoints& points, const std::vector<Pose>& before,
                           const std::vector<Pose>& after, double cell);

}  // namespace hba::render
