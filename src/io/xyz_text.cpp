// Plain-text point clouds (.xyz, as CloudCompare and many survey tools
// write them): one point a line, "x y z" or "x y z intensity", separated by
// spaces, tabs or commas. Blank lines and lines starting with '#' or '//'
// are skipped. Written with 17 significant digits: doubles come back to
// the bit.
#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cloud_view.hpp"
#include "hba/core/atomic_file.hpp"
#include "hba/core/error.hpp"
#include "hba/io/scan_formats.hpp"
#include "point_columns.hpp"

namespace hba::io {
namespace {

// The numbers of one line (empty for a blank or comment line).
std::vector<double> numbersOf(const std::filesystem::path& path, const std::string& line,
                              std::size_t number) {
  std::vector<double> values;
  const std::size_t start = line.find_first_not_of(" \t\r");
  if (start == std::string::npos || line[start] == '#' || line.compare(start, 2, "//") == 0) return values;
  const char* p = line.c_str() + start;
  while (*p != '\0') {
    char* end = nullptr;
    const double value = std::strtod(p, &end);
    if (end == p)
      failAt(path, fmt::format("line {}: '{}' is not a number", number, std::string(p).substr(0, 20)));
    values.push_back(value);
    p = end;
    while (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r') ++p;
  }
  return values;
}

template <typename Cloud>
Cloud readXyz(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) failAt(path, "cannot open for reading");
  Cloud cloud;
  std::size_t columns = 0;
  std::vector<std::vector<double>> rows;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::vector<double> values = numbersOf(path, line, number);
    if (values.empty()) continue;
    if (columns == 0) columns = values.size();
    if ((values.size() != 3 && values.size() != 4) || values.size() != columns) {
      failAt(path, fmt::format(
                       "line {}: {} numbers, expected {} (x y z or x y z intensity, the same on every line)",
                       number, values.size(), columns == 4 ? 4 : 3));
    }
    rows.push_back(std::move(values));
  }
  detail::PointCollector<Cloud> collector(cloud, /*wide=*/true, columns == 4);
  for (const std::vector<double>& row : rows) {
    const double values[4] = {row[0], row[1], row[2], columns == 4 ? row[3] : 0.0};
    collector.add(values);
  }
  collector.finish();
  return cloud;
}

void writeXyz(const std::filesystem::path& path, const detail::CloudView& cloud) {
  cloud.requireOneValuePerPoint(path);
  writeFileAtomically(
      path,
      [&](std::ostream& out) {
        for (std::size_t i = 0; i < cloud.size(); ++i) {
          const Vec3 p = cloud.world(i);
          out << fmt::format("{:.17g} {:.17g} {:.17g}", p.x(), p.y(), p.z());
          if (cloud.hasIntensity()) out << fmt::format(" {:.9g}", cloud.intensity(i));
          out << '\n';
        }
      },
      /*binary=*/false);
}

}  // namespace

ScanFormat xyzTextFormat() {
  return {".xyz",
          "XYZ text",
          true,
          &readXyz<PointCloud>,
          [](const std::filesystem::path& p, const PointCloud& c) { writeXyz(p, detail::CloudView(c)); },
          &readXyz<WideCloud>,
          [](const std::filesystem::path& p, const WideCloud& c) { writeXyz(p, detail::CloudView(c)); },
          [](const std::filesystem::path& p) -> std::uint64_t { return readXyz<WideCloud>(p).size(); },
          [](const std::filesystem::path& p) {
            ScanFileFields out{{"x", "y", "z"}, "XYZ text"};
            if (readXyz<WideCloud>(p).hasIntensity()) out.fields.push_back("intensity");
            return out;
          }};
}

}  // namespace hba::io
