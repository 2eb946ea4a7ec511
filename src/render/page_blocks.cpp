#include "page_blocks.hpp"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "hba/voxel/key_table.hpp"
#include "map_change.hpp"
#include "picture_points.hpp"

namespace hba::render {
namespace {

constexpr std::uint32_t kNoCell = ~0u;

template <typename T>
void appendLittleEndian(Bytes& out, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  // x86 and ARM are little endian; a big-endian host reverses the bytes.
  if constexpr (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__) std::reverse(raw, raw + sizeof(T));
  out.insert(out.end(), raw, raw + sizeof(T));
}

// The plane thickness of each point's cell with the map placed by `poses`
// (-1 where the cell's points form no plane). As CellMoments, but numbered
// by packed keys relative to a grid corner near the first pose: 16-byte
// slots against 32, and no list of keys (on nclt's 2 M points, CellMoments
// took about a tenth longer and more memory).
std::vector<float> thicknessPerPoint(const PagePoints& points, const std::vector<Pose>& poses, double cell) {
  const Vec3 corner =
      poses.empty() ? Vec3::Zero() : Vec3((poses.front().t / cell).array().floor().matrix() * cell);
  voxel::PackedVoxelIndex index;
  index.reserve(points.size() / 8);  // planes in 1 m cells at 0.1 m: tens of points a cell
  std::vector<CellMoments::Moments> moments;
  moments.reserve(points.size() / 8);
  std::vector<std::uint32_t> cell_of(points.size(), kNoCell);
  const double inverse = 1.0 / cell;
  forEachPlaced(points.points, poses, corner, [&](std::size_t i, const Vec3& q) {
    const std::uint64_t key = packedVoxelKey(q, inverse);
    if (key == kOutsidePackedRange) return;
    bool inserted = false;
    cell_of[i] = index.insert(key, inserted);
    if (inserted) moments.emplace_back();
    // Relative to the cell's own corner: precise far from the world origin.
    const Vec3 local = q - (q * inverse).array().floor().matrix() * cell;
    CellMoments::Moments& m = moments[cell_of[i]];
    m.count += 1.0;
    m.sum += local;
    m.outer += local * local.transpose();
  });
  std::vector<float> per_cell(moments.size());
  for (std::size_t c = 0; c < moments.size(); ++c) per_cell[c] = planeThicknessOf(moments[c]);
  std::vector<float> out(points.size(), -1.0f);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (cell_of[i] != kNoCell) out[i] = per_cell[cell_of[i]];
  return out;
}

}  // namespace

std::string base64(const Bytes& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v =
        (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) | bytes[i + 2];
    for (int shift : {18, 12, 6, 0}) out.push_back(kDigits[(v >> shift) & 63]);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (rest == 2) v |= std::uint32_t{bytes[i + 1]} << 8;
    out.push_back(kDigits[(v >> 18) & 63]);
    out.push_back(kDigits[(v >> 12) & 63]);
    out.push_back(rest == 2 ? kDigits[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

void writeBase64(std::ostream& os, const Bytes& bytes) {
  constexpr std::size_t kPiece = 3 * 65536;  // a multiple of 3: no padding between pieces
  Bytes piece;
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const std::size_t end = std::min(bytes.size(), at + kPiece);
    piece.assign(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                 bytes.begin() + static_cast<std::ptrdiff_t>(end));
    os << base64(piece);
  }
}

QuantizedPoints quantizePoints(const PagePoints& points) {
  float largest = 0.0f;
  for (const PagePoint& p : points.points) largest = std::max(largest, p.local.cwiseAbs().maxCoeff());
  QuantizedPoints out;
  out.step = std::max(1e-4, static_cast<double>(largest) / 32767.0);
  out.xyz.reserve(points.size() * 6);
  for (const PagePoint& p : points.points) {
    for (int axis = 0; axis < 3; ++axis) {
      const double q = std::round(p.local(axis) / out.step);
      appendLittleEndian(out.xyz, static_cast<std::int16_t>(std::clamp(q, -32767.0, 32767.0)));
    }
  }
  return out;
}

Bytes pointsPerScan(const PagePoints& points, std::size_t frames) {
  std::vector<std::uint32_t> counts(frames, 0);
  for (const PagePoint& p : points.points) ++counts.at(p.scan);
  Bytes out;
  out.reserve(frames * 4);
  for (const std::uint32_t count : counts) appendLittleEndian(out, count);
  return out;
}

Bytes intensityCodes(const PagePoints& points) {
  if (!points.has_intensity) return {};
  std::vector<float> sorted(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) sorted[i] = points.points[i].intensity;
  const auto at = [&](double fraction) {
    auto nth =
        sorted.begin() + static_cast<std::ptrdiff_t>(fraction * static_cast<double>(sorted.size() - 1));
    std::nth_element(sorted.begin(), nth, sorted.end());
    return static_cast<double>(*nth);
  };
  const double low = at(0.01);
  const double high = std::max(at(0.99), low + 1e-6);
  Bytes out;
  out.reserve(points.size());
  for (const PagePoint& p : points.points) {
    const double v = p.intensity;
    out.push_back(
        static_cast<std::uint8_t>(std::clamp(std::round((v - low) / (high - low) * 255.0), 0.0, 255.0)));
  }
  return out;
}

Bytes poseRows(const std::vector<Pose>& poses, const Vec3& origin) {
  Bytes out;
  out.reserve(poses.size() * 48);
  for (const Pose& pose : poses) {
    const Mat3 R = pose.R();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) appendLittleEndian(out, static_cast<float>(R(r, c)));
    const Vec3 t = pose.t - origin;
    for (int axis = 0; axis < 3; ++axis) appendLittleEndian(out, static_cast<float>(t(axis)));
  }
  return out;
}

Bytes thicknessChangeCodes(const PagePoints& points, const std::vector<Pose>& before,
                           const std::vector<Pose>& after, double cell) {
  std::vector<float> thick_before, thick_after;
  tbb::parallel_invoke([&] { thick_before = thicknessPerPoint(points, before, cell); },
                       [&] { thick_after = thicknessPerPoint(points, after, cell); });
  Bytes out(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (thick_before[i] < 0.0f || thick_after[i] < 0.0f) continue;
    const double steps = std::round((thick_before[i] - thick_after[i]) * 1000.0 / kChangeStepMm);
    out[i] = static_cast<std::uint8_t>(128.0 + std::clamp(steps, -127.0, 127.0));
  }
  return out;
}

}  // namespace hba::render
