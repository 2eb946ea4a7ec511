// writePly: one vertex element with float x y z [intensity], written atomically.
// A cloud with an origin (a map far from the world origin) gets double x y z:
// origin + point; so does a WideCloud with a coordinate that is not exactly a float.
#include <charconv>
#include <cstring>
#include <string>

#include "cloud_view.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/io/ply.hpp"

namespace hba::io {
namespace {
using detail::CloudView;

std::string plyHeaderText(const CloudView& cloud, PlyEncoding encoding) {
  std::string text = "ply\nformat ";
  text += encoding == PlyEncoding::Ascii ? "ascii" : "binary_little_endian";
  text += " 1.0\ncomment written by hba\nelement vertex " + std::to_string(cloud.size()) + "\n";
  const char* type = cloud.wide() ? "double" : "float";
  for (const char* axis : {"x", "y", "z"}) text += std::string("property ") + type + " " + axis + "\n";
  if (cloud.hasIntensity()) text += "property float intensity\n";
  text += "end_header\n";
  return text;
}

void appendAscii(const CloudView& cloud, std::string& out) {
  char text[32];
  const auto append = [&](auto value) {
    // Shortest text that parses back to the same value: ascii round-trips exactly.
    out.append(text, std::to_chars(text, text + sizeof(text), value).ptr);
  };
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      if (axis > 0) out += ' ';
      cloud.wide() ? append(cloud.world(i)[axis]) : append(cloud.point(i)[axis]);
    }
    if (cloud.hasIntensity()) {
      out += ' ';
      append(cloud.intensity(i));
    }
    out += '\n';
  }
}

void appendWideBinary(const CloudView& cloud, std::string& out) {
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3 p = cloud.world(i);
    const double xyz[3] = {p.x(), p.y(), p.z()};
    out.append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
    if (cloud.hasIntensity()) {
      const float value = cloud.intensity(i);
      out.append(reinterpret_cast<const char*>(&value), sizeof(float));
    }
  }
}

void appendBinary(const CloudView& cloud, std::string& out) {
  if (cloud.wide()) return appendWideBinary(cloud, out);
  const std::size_t values = cloud.hasIntensity() ? 4 : 3;
  const std::size_t start = out.size();
  out.resize(start + cloud.size() * values * sizeof(float));
  char* cursor = &out[start];
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3f p = cloud.point(i);
    const float record[4] = {p.x(), p.y(), p.z(), cloud.hasIntensity() ? cloud.intensity(i) : 0.0f};
    std::memcpy(cursor, record, values * sizeof(float));
    cursor += values * sizeof(float);
  }
}

}  // namespace

namespace detail {

void writePlyView(const std::filesystem::path& path, const CloudView& cloud, PlyEncoding encoding) {
  cloud.requireOneValuePerPoint(path);
  std::string content = plyHeaderText(cloud, encoding);
  if (encoding == PlyEncoding::Ascii) {
    appendAscii(cloud, content);
  } else {
    appendBinary(cloud, content);
  }
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace detail

void writePly(const std::filesystem::path& path, const PointCloud& cloud, PlyEncoding encoding) {
  detail::writePlyView(path, CloudView(cloud), encoding);
}

}  // namespace hba::io
