// writePcd: fields x y z [intensity] as float32 [time as float64], written atomically. The file
// is assembled in memory and written with one call. A cloud with an origin
// (a map far from the world origin) gets float64 x y z: origin + point; so
// does a WideCloud with a coordinate that is not exactly a float.
#include <charconv>
#include <cstring>
#include <string>

#include "cloud_view.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/pcd.hpp"
#include "lzf_block.hpp"

namespace hba::io {
namespace {
namespace fs = std::filesystem;

const char* encodingName(PcdEncoding encoding) {
  switch (encoding) {
    case PcdEncoding::Ascii:
      return "ascii";
    case PcdEncoding::Binary:
      return "binary";
    case PcdEncoding::BinaryCompressed:
      return "binary_compressed";
  }
  return "binary";
}

using detail::CloudView;

std::string pcdHeaderText(const CloudView& cloud, PcdEncoding encoding) {
  const bool with_i = cloud.hasIntensity(), with_t = cloud.hasTime();
  const std::string n = std::to_string(cloud.size());
  std::string fields = "x y z", sizes = cloud.wide() ? "8 8 8" : "4 4 4", types = "F F F", counts = "1 1 1";
  const auto addField = [&](const char* name, const char* size) {
    fields += std::string(" ") + name;
    sizes += std::string(" ") + size;
    types += " F";
    counts += " 1";
  };
  if (with_i) addField("intensity", "4");
  if (with_t) addField("time", "8");
  std::string text = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n";
  text += "FIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types + "\nCOUNT " + counts + "\n";
  text += "WIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\n";
  text += std::string("DATA ") + encodingName(encoding) + "\n";
  return text;
}

// Fields written: x, y, z and, when the cloud has them, intensity and time.
std::size_t fieldCount(const CloudView& cloud) {
  return 3 + (cloud.hasIntensity() ? 1 : 0) + (cloud.hasTime() ? 1 : 0);
}

template <typename T>
void appendValue(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

// Shortest text that parses back to the same value: ascii round-trips exactly.
template <typename T>
void appendText(std::string& out, T value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  out.append(text, result.ptr);
}

// Appends field `field` of point `point` as the header declares it.
template <bool kText>
void appendField(const CloudView& cloud, std::size_t point, std::size_t field, std::string& out) {
  if (field == 3 && cloud.hasIntensity()) {
    kText ? appendText(out, cloud.intensity(point)) : appendValue(out, cloud.intensity(point));
  } else if (field >= 3) {
    kText ? appendText(out, cloud.time(point)) : appendValue(out, cloud.time(point));
  } else if (cloud.wide()) {
    const double v = cloud.world(point)[static_cast<Eigen::Index>(field)];
    kText ? appendText(out, v) : appendValue(out, v);
  } else {
    const float v = cloud.point(point)[static_cast<Eigen::Index>(field)];
    kText ? appendText(out, v) : appendValue(out, v);
  }
}

void appendAscii(const CloudView& cloud, std::string& out) {
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (std::size_t f = 0; f < fieldCount(cloud); ++f) {
      if (f > 0) out += ' ';
      appendField<true>(cloud, i, f, out);
    }
    out += '\n';
  }
}

void appendBinary(const CloudView& cloud, std::string& out) {
  out.reserve(out.size() + cloud.size() * fieldCount(cloud) * sizeof(double));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (std::size_t f = 0; f < fieldCount(cloud); ++f) appendField<false>(cloud, i, f, out);
  }
}

// Column-major (all x, then all y, ...) compresses far better than records.
void appendCompressed(const CloudView& cloud, std::string& out, const fs::path& path) {
  std::string columns;
  columns.reserve(cloud.size() * fieldCount(cloud) * sizeof(double));
  for (std::size_t f = 0; f < fieldCount(cloud); ++f) {
    for (std::size_t i = 0; i < cloud.size(); ++i) appendField<false>(cloud, i, f, columns);
  }
  const std::size_t sizes_at = out.size();
  appendValue<std::uint32_t>(out, 0);
  appendValue(out, static_cast<std::uint32_t>(columns.size()));
  const std::size_t compressed = detail::lzfCompressAppend(columns, out, path);
  const auto compressed32 = static_cast<std::uint32_t>(compressed);
  std::memcpy(&out[sizes_at], &compressed32, sizeof(compressed32));
}

}  // namespace

namespace detail {

void writePcdView(const fs::path& path, const CloudView& cloud, PcdEncoding encoding) {
  cloud.requireOneValuePerPoint(path);
  std::string content = pcdHeaderText(cloud, encoding);
  switch (encoding) {
    case PcdEncoding::Ascii:
      appendAscii(cloud, content);
      break;
    case PcdEncoding::Binary:
      appendBinary(cloud, content);
      break;
    case PcdEncoding::BinaryCompressed:
      appendCompressed(cloud, content, path);
      break;
  }
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace detail

void writePcd(const fs::path& path, const PointCloud& cloud, PcdEncoding encoding) {
  detail::writePcdView(path, CloudView(cloud), encoding);
}

}  // namespace hba::io
