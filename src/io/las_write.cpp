// writeLas: LAS 1.4, point data record format 6, no VLRs. Coordinates are
// millimetres (scale 0.001) from an offset at the cloud's centre in whole
// metres, so UTM-size maps keep millimetres within the int32 range.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <limits>
#include <string>

#include "cloud_view.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/las.hpp"
#include "las_format.hpp"

namespace hba::io {
namespace {
namespace field = detail::las_field;
using detail::CloudView;
using detail::storeLittleEndian;

constexpr double kScale = 0.001;  // m per integer step
constexpr std::uint8_t kReturnOneOfOne = 0x11;
// Global encoding bit 4: the CRS, if any, is WKT (the only kind formats 6-10 may use).
constexpr std::uint16_t kWktEncoding = 1u << 4;

struct Quantization {
  Vec3 offset = Vec3::Zero();
  Vec3 min = Vec3::Zero();  // of the stored (rounded) coordinates
  Vec3 max = Vec3::Zero();
};

template <typename T>
void requireOnePerPoint(const std::vector<T>& values, const CloudView& cloud, const std::string& what,
                        const std::filesystem::path& path) {
  if (!values.empty() && values.size() != cloud.size()) {
    failAt(path, "cannot write: the cloud has " + std::to_string(cloud.size()) + " points but " +
                     std::to_string(values.size()) + " " + what);
  }
}

Quantization chooseQuantization(const CloudView& cloud, const std::filesystem::path& path) {
  Quantization q;
  if (cloud.empty()) return q;
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 p = cloud.world(i);
    if (!p.allFinite()) failAt(path, "cannot write point " + std::to_string(i) + ": not a finite coordinate");
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  q.offset = ((low + high) / 2.0).array().round();
  constexpr double kLimit = std::numeric_limits<std::int32_t>::max() * kScale;
  const double reach =
      std::max((high - q.offset).cwiseAbs().maxCoeff(), (low - q.offset).cwiseAbs().maxCoeff());
  if (reach >= kLimit) {
    failAt(path, "cannot write: the cloud spans " + std::to_string(reach * 2.0) +
                     " m, beyond what LAS int32 millimetres can hold");
  }
  for (int a = 0; a < 3; ++a) {
    q.min[a] = std::round((low[a] - q.offset[a]) / kScale) * kScale + q.offset[a];
    q.max[a] = std::round((high[a] - q.offset[a]) / kScale) * kScale + q.offset[a];
  }
  return q;
}

std::uint16_t lasIntensity(const CloudView& cloud, std::size_t i) {
  if (!cloud.hasIntensity() || !(cloud.intensity(i) > 0.0f)) return 0;  // none, negative or NaN
  return static_cast<std::uint16_t>(std::lround(std::min(cloud.intensity(i), 65535.0f)));
}

void putText(std::string& header, std::size_t at, const std::string& text) {
  header.replace(at, std::min(text.size(), detail::kLasTextFieldBytes), text, 0, detail::kLasTextFieldBytes);
}

void putVec3(std::string& header, std::size_t at, const Vec3& v) {
  for (int a = 0; a < 3; ++a) storeLittleEndian(&header[at + 8 * a], v[a]);
}

std::string headerBytes(const CloudView& cloud, const Quantization& q) {
  std::string header(detail::kLasHeaderSize14, '\0');
  header.replace(field::kSignature, 4, "LASF");
  storeLittleEndian<std::uint16_t>(&header[field::kGlobalEncoding], kWktEncoding);
  header[field::kVersionMajor] = 1;
  header[field::kVersionMinor] = 4;
  putText(header, field::kSystemIdentifier, "OTHER");
  putText(header, field::kGeneratingSoftware, std::string("hba ") + HBA_IO_VERSION);
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  storeLittleEndian<std::uint16_t>(&header[field::kCreationDay], static_cast<std::uint16_t>(utc.tm_yday + 1));
  storeLittleEndian<std::uint16_t>(&header[field::kCreationYear],
                                   static_cast<std::uint16_t>(utc.tm_year + 1900));
  storeLittleEndian<std::uint16_t>(&header[field::kHeaderSize], detail::kLasHeaderSize14);
  storeLittleEndian<std::uint32_t>(&header[field::kPointDataOffset], detail::kLasHeaderSize14);
  header[field::kPointFormat] = 6;
  storeLittleEndian<std::uint16_t>(&header[field::kRecordLength], detail::las_point6::kLength);
  // The legacy counts stay zero: LAS 1.4 requires it for formats 6-10.
  putVec3(header, field::kScale, Vec3::Constant(kScale));
  putVec3(header, field::kOffset, q.offset);
  for (int a = 0; a < 3; ++a) {
    storeLittleEndian(&header[field::kBounds + 16 * a], q.max[a]);
    storeLittleEndian(&header[field::kBounds + 16 * a + 8], q.min[a]);
  }
  const auto count = static_cast<std::uint64_t>(cloud.size());
  storeLittleEndian(&header[field::kPointCount], count);
  storeLittleEndian(&header[field::kPointsByReturn], count);  // every point is return 1
  return header;
}

void appendRecords(const CloudView& cloud, const LasPointExtras& extras, const Quantization& q,
                   std::string& out) {
  namespace point = detail::las_point6;
  const std::size_t start = out.size();
  out.resize(start + cloud.size() * point::kLength, '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    char* record = &out[start + i * point::kLength];
    const Vec3 p = cloud.world(i);
    for (int a = 0; a < 3; ++a) {
      const auto steps = static_cast<std::int32_t>(std::lround((p[a] - q.offset[a]) / kScale));
      storeLittleEndian(record + detail::las_point::kX + 4 * a, steps);
    }
    storeLittleEndian(record + detail::las_point::kIntensity, lasIntensity(cloud, i));
    record[point::kReturns] = static_cast<char>(kReturnOneOfOne);
    if (!extras.scan_index.empty()) {
      const std::uint32_t scan = std::min<std::uint32_t>(extras.scan_index[i], 65535);
      storeLittleEndian(record + point::kPointSourceId, static_cast<std::uint16_t>(scan));
    }
    storeLittleEndian(record + point::kGpsTime, extras.gps_time.empty() ? 0.0 : extras.gps_time[i]);
  }
}

}  // namespace

namespace detail {

void writeLasView(const std::filesystem::path& path, const CloudView& cloud, const LasPointExtras& extras) {
  cloud.requireOneValuePerPoint(path);
  requireOnePerPoint(extras.scan_index, cloud, "scan indices", path);
  requireOnePerPoint(extras.gps_time, cloud, "GPS times", path);
  const Quantization q = chooseQuantization(cloud, path);
  std::string content = headerBytes(cloud, q);
  appendRecords(cloud, extras, q, content);
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace detail

void writeLas(const std::filesystem::path& path, const PointCloud& cloud, const LasPointExtras& extras) {
  detail::writeLasView(path, CloudView(cloud), extras);
}

}  // namespace hba::io
